// A kind of machine, one interface: a 3-axis mill, a trunnion table indexed between setups (3+2), a trunnion with
// tool-centre-point control (simultaneous five-axis); next a robot arm. Each answers for itself what the job runner,
// the post and the checks ask of a machine: its joints and their limits, where its joints put the tool (forward
// kinematics) and which joints put the tool at a pose (inverse, the branch nearest the joints before kept), how a
// setup's side of the part comes under the tool (re-clamped by hand, or turned by the machine's joints), and whether
// it cuts with the tool axis changing (its programs then give a tool axis at every move).
//
// Poses are in the workpiece frame as the machine holds it: the part's frame as clamped, which on a trunnion is the
// table's frame at A = C = 0 (machine/trunnion.hpp), on a mill the machine's own axes. The tool axis points from the
// tip towards the spindle.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rosmill/geometry/types.hpp"
#include "rosmill/machine/trunnion.hpp"

namespace rosmill::core::machine {

struct Joint {
  std::string name;     // the controller's axis letter (X, Y, Z, A, C) or an arm's joint name
  bool rotary = false;  // degrees; else millimetres
  double min = -INFINITY, max = INFINITY;
  double velocity = 0;      // per second (0: the file states none)
  double acceleration = 0;  // per second squared (0: none stated)
  bool within(double v) const { return v >= min - 1e-9 && v <= max + 1e-9; }
};

// A machine's joint values, in the order of its joints().
using JointValues = std::vector<double>;

struct ToolPose {
  Vec3 tip = Vec3::Zero();    // mm
  Vec3 axis = Vec3::UnitZ();  // unit
};

class Machine {
 public:
  virtual ~Machine() = default;
  // What it is, for messages and reports: "3-axis mill", "trunnion (3+2)", "trunnion with tool-centre-point control".
  virtual std::string kind() const = 0;
  virtual const std::vector<Joint>& joints() const = 0;
  // Where the joints put the tool.
  virtual ToolPose forward(const JointValues& q) const = 0;
  // The joints that put the tool at `pose`, on the branch nearest `near` (the least motion of the slowest joint,
  // then the least motion in all); empty when no solution keeps every joint in its limits, `why` then says why.
  virtual std::optional<JointValues> inverse(const ToolPose& pose, const JointValues& near,
                                             std::string* why = nullptr) const = 0;
  // True when the machine turns the part between setups with its own joints (one clamping for the job); false when
  // the part is re-clamped by hand, each setup under the spindle's own axis.
  virtual bool turns_part() const = 0;
  // True when it cuts with the tool axis changing along a move (its toolpaths give an axis at every move).
  virtual bool simultaneous() const = 0;
  // The joints that bring a setup whose tool axis is `direction` (workpiece frame, unit) under the tool, from the
  // joints at `near`: where they are on a machine that re-clamps (every side is a setup a fixture can hold); the
  // rotary joints that turn it there on one that turns the part, empty (with `why`) where none can.
  virtual std::optional<JointValues> setup_joints(const Vec3& direction, const JointValues& near,
                                                  std::string* why = nullptr) const = 0;
  // The trunnion table it carries, if any: the post, the indexing sweep and the rotary verifier model it.
  virtual const Trunnion* trunnion() const { return nullptr; }

  // The joint named `name` (a controller's axis letter), or null.
  const Joint* joint(const std::string& name) const;
  // The joints at rest: each one's zero, or the end of its range nearest zero.
  JointValues home() const;
  // Whether every joint of `q` lies in its limits; `why` names the first that does not.
  bool within_limits(const JointValues& q, std::string* why = nullptr) const;
};

// The linear joints X Y Z of a machine over `travel` (mm), at these velocities (mm/s) and accelerations (mm/s^2).
std::vector<Joint> linear_joints(const Box3& travel, const Vec3& velocity, const Vec3& acceleration);

// A 3-axis mill: joints X Y Z over `travel` (machine coordinates of the tool tip), the tool along machine +Z.
std::shared_ptr<const Machine> three_axis_mill(const Box3& travel, const Vec3& velocity, const Vec3& acceleration);
// A trunnion mill (XYZAC): X Y Z over `travel`, A and C as the trunnion gives them. Its mode decides the kind:
// identity kinematics indexes between setups (3+2); tool-centre-point control cuts with A and C moving too.
std::shared_ptr<const Machine> trunnion_mill(const Trunnion& trunnion, const Box3& travel, const Vec3& velocity,
                                             const Vec3& acceleration);

// The A and C of a trunnion machine's joints (its fourth and fifth).
inline Index index_of(const JointValues& q) { return Index{q.at(3), q.at(4)}; }

}  // namespace rosmill::core::machine
