// A machining setup: the tool axis in the workpiece frame and the placement of the workpiece in the setup's frame.
// Planning happens with the tool pointing down the machine's Z: for a setup the part is turned over (re-fixtured)
// so that the setup's tool axis becomes +Z, and the toolpath of that setup is written in the setup's frame. The
// setup frame's origin is the setup's datum (the program's zero, where its work offset G54..G59 lies): the
// workpiece origin turned, or a point of the stock a machinist touches off (setup_datum.hpp in the job area).
#pragma once
#include <string>

#include "rosmill/geometry/placement.hpp"

namespace rosmill::core {

// The name the workpiece frame has in placements.
inline const std::string kWorkpieceFrame = "workpiece";

struct SetupFrame {
  std::string name;                 // "+Z", "-X", ... or "custom"
  Vec3 tool_axis = Vec3::UnitZ();   // unit, from the tool tip towards the spindle, in the workpiece frame
  // The workpiece in the setup's frame: the tool axis maps onto +Z. Planning works in the setup frame.
  Placement placement{"setup +Z", kWorkpieceFrame, Eigen::Isometry3d::Identity()};

  Vec3 to_setup_frame(const Vec3& p) const { return placement.point(p); }
  Vec3 to_workpiece_frame(const Vec3& p) const { return placement.point_back(p); }
  Vec3 direction_to_setup(const Vec3& d) const { return placement.direction(d); }
  Eigen::Quaterniond rotation() const { return placement.rotation(); }  // workpiece -> setup
  bool identity() const { return placement.identity(); }
  // The same setup with its frame's origin moved to `origin` (given in the setup frame as it is).
  SetupFrame with_origin(const Vec3& origin) const;
  // True when both turn the part the same way and put it in the same place.
  bool same_as(const SetupFrame& other) const;
};

// Throws Error naming `where` when the setup's tool axis or placement holds NaN or infinity, the axis is not a unit
// vector, the placement is not rigid, or it does not turn the axis onto +Z.
void check_setup(const SetupFrame& setup, const std::string& where = "setup");

// "+Z", "-Z", "+X", "-X", "+Y", "-Y" (case-insensitive, "Z" means "+Z"); throws Error(where) on anything else.
SetupFrame named_setup(const std::string& name, const std::string& where = "setup");
// A tool direction; throws Error(where) when it is not finite or has (near) zero length.
SetupFrame direction_setup(const Vec3& direction, const std::string& where = "direction");
// The setup named, or, when name is empty, the one of `direction`.
SetupFrame resolve_setup(const std::string& name, const Vec3& direction);
// "+Z"-style for an axis direction (within 1e-9), else "custom".
std::string setup_name_of(const Vec3& direction);

}  // namespace rosmill::core
