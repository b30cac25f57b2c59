// A trunnion table (XYZAC, "table-rotary-tilting"): the A axis tilts a cradle about machine X, and the C axis turns
// the round table on it about the cradle's Z. The spindle stays vertical; the part turns under it. With A and C
// indexed and held, a 3-axis program cuts the part from another side (3+2 machining).
//
// The chain, as LinuxCNC's xyzac-trt kinematics models it (src/emc/kinematics/trtfuncs.c): a point p of the table
// (its coordinates at A = C = 0, machine axes) goes to the machine point
//   M(p) = R_x(a) (R_z(c) (p - centre) - pivot) + pivot + centre,
// `centre` the point the C axis passes through at A = 0 (the x/y/z-rot-point pins) and `pivot` the A axis's place
// relative to it (0, y-offset, z-offset). The tool axis d of a setup (a direction of the table, from the tip
// towards the spindle) is brought onto machine +Z when R_x(a) R_z(c) d = +Z: cos a = d.z, and C turns d's XY part
// onto +Y (sin a > 0) or -Y (sin a < 0). Two solutions where the axis is tilted; one A and any C for +Z.
#pragma once
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "rosmill/geometry/placement.hpp"
#include "rosmill/geometry/types.hpp"

namespace rosmill::core::machine {

struct RotaryAxis {
  double min = 0, max = 0;          // degrees
  double velocity = 0;              // degrees/s
  double acceleration = 0;          // degrees/s^2
};

// Which coordinates the programs are written in: identity kinematics (LinuxCNC's M429: the program's X Y Z are the
// machine's axes, the part's points turned about the pivots by the post) or tool-centre-point kinematics (M428: the
// program's X Y Z are the table's, the controller turns them).
enum class KinematicsMode { Identity, ToolCentrePoint };

struct Trunnion {
  RotaryAxis a, c;
  Vec3 centre = Vec3::Zero();       // the C axis at A = 0 passes through this machine point (mm)
  Vec3 pivot = Vec3::Zero();        // the A axis relative to `centre` (x ignored: A turns about machine X)
  KinematicsMode mode = KinematicsMode::Identity;
  double safe_z = 0;                // machine Z (G53) the spindle retracts to before the part turns (mm)
  // The longest tool's length offset (the controller's tool table Z: gauge line to tip): at the safe Z its tip hangs
  // this far below it, and the part must turn under it (mm).
  double max_tool_length = 0;

  // The machine point of table point p with the axes at a, c (degrees).
  Vec3 machine_point(const Vec3& p, double a, double c) const;
  // The table point at machine point m with the axes at a, c.
  Vec3 table_point(const Vec3& m, double a, double c) const;
  // The tool axis on the table (its frame at A = C = 0) with the axes at a, c: machine +Z turned back by them.
  Vec3 tool_axis(double a, double c) const;
  // The placement of the table in the machine frame at a, c: "table" in "machine".
  Placement table_in_machine(double a, double c) const;
  bool a_in_range(double a) const { return a >= this->a.min - 1e-9 && a <= this->a.max + 1e-9; }
  bool c_in_range(double c) const { return c >= this->c.min - 1e-9 && c <= this->c.max + 1e-9; }
};

struct Index {
  double a = 0, c = 0;  // degrees
};

// The A and C that bring tool axis `d` (table frame, unit) onto machine +Z, inside the ranges, with the least rotary
// motion from `from` (the larger of the two axes' times at their velocities, then the sum of the angles); C is taken
// among its turns by 360 degrees. Empty when no solution lies in the ranges; `why` then says what it would take.
std::optional<Index> index_for(const Trunnion& t, const Vec3& d, const Index& from, std::string* why = nullptr);

// The machine's linear joints along a move under tool-centre-point control: the tip straight on the table from
// `from` to `to` (table points, mm), A and C in proportion from i0 to i1, so that the joints follow a curve. Sampled
// every millimetre of the tip or degree of A or C, at most 4,096 samples (a longer, or hostile, move coarser): the
// joints' extent and the length of each one's path.
struct JointSweep {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  Vec3 travel = Vec3::Zero();
};
JointSweep sweep_joints(const Trunnion& t, const Vec3& from, const Vec3& to, const Index& i0, const Index& i1);

// The A and C at every tool axis of a multi-axis path (table frame, unit), for tool-centre-point control: at each
// axis one of its two solutions (A and -A, C half a turn apart; any C on the pole, where the axis is the table's),
// chosen over the whole path for the least rotary motion (the larger of the two axes' times at their velocities,
// summed over the steps), from `from`. C keeps its winding (each C the turn nearest the one before, never wrapped
// to a range of 360), and a path through or near the pole changes A's sign there rather than turning C by half a
// turn. Empty when some axis has no solution in the ranges; `why` then names it.
std::optional<std::vector<Index>> indexes_along(const Trunnion& t, const std::vector<Vec3>& axes, const Index& from,
                                                std::string* why = nullptr);

}  // namespace rosmill::core::machine
