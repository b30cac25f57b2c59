// Safety before anything is sent: the machine's limits (config/machine.yaml) and the checker that refuses a
// program breaking one, naming the line and the limit.
#pragma once
#include <string>
#include <vector>

#include <optional>

#include "rosmill/gcode/trajectory_limits.hpp"
#include "rosmill/gcode/work_offset.hpp"
#include "rosmill/geometry/types.hpp"
#include "rosmill/machine/machine.hpp"
#include "rosmill/machine/trunnion.hpp"

namespace rosmill::core::gcode {

// Lengths in mm, feeds in mm/min. Envelope and table are in machine coordinates; the program's coordinates are
// the work offset's (G54), whose origin sits at `work_offset` in machine coordinates unless the program sets G54
// itself (G10 L2 P1 before its moves, see work_offset.hpp).
struct MachineLimits {
  std::string name;
  Box3 envelope;                  // soft limits of the controlled point (the tool tip)
  WorkOffset work_offset;
  double table_z = 0.0;           // no tool tip goes below the table top
  double max_feed = 0.0;
  double max_spindle_rpm = 0.0;
  double clearance_over_stock = 0.0;  // rapids end at least this high over the stock top
  // Per axis (mm/s^2; zero where the file gives none): the time estimate's accelerations.
  Vec3 max_acceleration = Vec3::Zero();
  // The controller's trajectory planner (`trajectory:`; its max_acceleration is the one above, its rotary limits
  // the trunnion's): what times a program (cycle_time.hpp).
  TrajectoryLimits trajectory;
  // Machine X and Y over which a job's setups centre the stock in its fixture (where the vise sits on the table):
  // each setup's work offset (G54..G59) is its datum there. The work offset's X and Y unless the file gives it.
  Vec2 fixture_position = Vec2::Zero();
  // A trunnion table (machine/trunnion.hpp) when the file has `rotary:`: its A and C ranges are limits like the
  // envelope, and a job's setups become A/C indexing in one program (3+2).
  std::optional<machine::Trunnion> trunnion;

  // The kind of machine these limits describe (machine/machine.hpp): a 3-axis mill, or a trunnion mill in the mode
  // its file gives, its joints over the envelope at the trajectory's velocities and accelerations.
  std::shared_ptr<const machine::Machine> machine() const;
};

// Reads and validates the YAML file; throws Error naming the file and the field.
MachineLimits load_machine_limits(const std::string& path);
// The same from YAML text; `path` stands for the file in messages.
MachineLimits parse_machine_limits(const std::string& yaml_text, const std::string& path);

struct LimitViolation {
  size_t line = 0;       // 1-based program line
  std::string limit;     // which limit: "envelope x max", "table", "max feed", "rapid clearance", ...
  std::string detail;    // the value against the limit
  std::string text;      // the program line
  std::string message() const;
};

struct LimitCheckOptions {
  // Top of the stock in program coordinates; NaN: the highest Z of the cutting moves that travel in XY (the stock
  // reaches at least there).
  double stock_top = NAN;
  // The caller swept every rapid through a model of the stock that knows its top under each one (a job's
  // in-process stock refuses a rapid into material): a rapid then need not clear the whole stock's top.
  bool rapids_checked_by_stock = false;
  size_t max_violations = 20;
};

std::vector<LimitViolation> check_limits(const std::vector<std::string>& lines, const MachineLimits& limits,
                                         const LimitCheckOptions& options = {});
// Throws Error("line N", "<limit>: <detail>: <text>") for the first violation (and counts the others).
void require_within_limits(const std::vector<std::string>& lines, const MachineLimits& limits,
                           const LimitCheckOptions& options = {});

}  // namespace rosmill::core::gcode
