// static_frame: places one frame in another for the whole session, latched on /tf_static (Debian's ROS ships the
// tf2 library without tf2_ros's static_transform_publisher program). Where the workpiece sits on the machine table
// or in the cell, where the scanner is mounted. Parameters (all checked at start-up):
//   parent, child   frame names (different, not empty)
//   xyz             [x, y, z] in metres
//   rpy             [roll, pitch, yaw] in radians (fixed axes X, then Y, then Z)
// The frame it publishes is on /diagnostics, as every node's input is.
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <Eigen/Geometry>
#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/input_diagnostics.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"

namespace rosmill::edge {
namespace {

class StaticFrame {
 public:
  StaticFrame(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh) : diagnostics_(nh) {
    const std::string parent = string_param(pnh, "parent", "");
    const std::string child = string_param(pnh, "child", "");
    if (parent.empty() || child.empty() || parent == child)
      throw Error("parameters " + pnh.resolveName("parent") + " and child", "must name two different frames");
    const Vec3 xyz = vector_param(pnh, "xyz"), rpy = vector_param(pnh, "rpy");
    const Eigen::Quaterniond q = Eigen::AngleAxisd(rpy.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Vec3::UnitY()) *
                                 Eigen::AngleAxisd(rpy.x(), Vec3::UnitX());
    broadcaster_.sendTransform(to_transform_msg(parent, child, q, xyz));
    ROS_INFO("static_frame: %s in %s at [%g %g %g] m, rpy [%g %g %g] rad", child.c_str(), parent.c_str(), xyz.x(),
             xyz.y(), xyz.z(), rpy.x(), rpy.y(), rpy.z());
    diagnostics_.accepted("frame", child + " published in " + parent);
  }

 private:
  // Three finite numbers (missing: zero).
  static Vec3 vector_param(const ::ros::NodeHandle& nh, const std::string& name) {
    std::vector<double> v;
    if (!nh.hasParam(name)) return Vec3::Zero();
    if (!nh.getParam(name, v) || v.size() != 3 || !std::isfinite(v[0] + v[1] + v[2]))
      throw Error("parameter " + nh.resolveName(name), "must be a list of three finite numbers");
    return {v[0], v[1], v[2]};
  }

  InputDiagnostics diagnostics_;
  tf2_ros::StaticTransformBroadcaster broadcaster_;
};

}  // namespace
}  // namespace rosmill::edge

int main(int argc, char** argv) {
  return rosmill::edge::run_node<rosmill::edge::StaticFrame>(argc, argv, "static_frame");
}
