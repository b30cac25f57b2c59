// A machining setup: the tool axis in the workpiece frame and the rotation that turns it onto +Z. Planning happens
// with the tool pointing down the machine's Z: for a setup the part is turned over (re-fixtured) so that the setup's
// tool axis becomes +Z, and the toolpath of that setup is written in the turned part's frame.
#pragma once
#include <Eigen/Geometry>
#include <string>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/segment/setup_filter.hpp"

namespace rosmill::core {

struct SetupFrame {
  std::string name;                 // "+Z", "-X", ... or "custom"
  Vec3 tool_axis = Vec3::UnitZ();   // unit, from the tool tip towards the spindle, in the workpiece frame
  // Workpiece frame -> setup frame (tool_axis becomes +Z). Planning works in the setup frame.
  Eigen::Quaterniond to_setup = Eigen::Quaterniond::Identity();

  Vec3 to_setup_frame(const Vec3& p) const { return to_setup * p; }
  Vec3 to_workpiece_frame(const Vec3& p) const { return to_setup.conjugate() * p; }
  bool identity() const { return to_setup.angularDistance(Eigen::Quaterniond::Identity()) < 1e-12; }
};

// Throws Error naming `where` when the setup's tool axis or rotation holds NaN or infinity, the axis is not a unit
// vector, the rotation not a unit quaternion, or the rotation does not turn the axis onto +Z.
void check_setup(const SetupFrame& setup, const std::string& where = "setup");

// "+Z", "-Z", "+X", "-X", "+Y", "-Y" (case-insensitive, "Z" means "+Z"); throws Error(where) on anything else.
SetupFrame named_setup(const std::string& name, const std::string& where = "setup");
// A tool direction; throws Error(where) when it is not finite or has (near) zero length.
SetupFrame direction_setup(const Vec3& direction, const std::string& where = "direction");
// The setup named, or, when name is empty, the one of `direction`.
SetupFrame resolve_setup(const std::string& name, const Vec3& direction);

// The segmentation's filter of a setup: named ("+Z", "z", "-x", "4axis:x", "5axis", any case) or, when name is
// empty, the 3-axis setup of `direction`. Its name is "+Z"-style for 3-axis setups. Throws Error naming `where`.
segment::SetupFilter setup_filter_of(const std::string& name, const Vec3& direction, double max_angle_deg,
                                     const std::string& where = "setup");

// Copies rotated into the setup frame (returned unchanged when the setup is +Z).
Mesh mesh_in_setup(const Mesh& mesh, const SetupFrame& setup);
PointCloud cloud_in_setup(const PointCloud& cloud, const SetupFrame& setup);

}  // namespace rosmill::core
