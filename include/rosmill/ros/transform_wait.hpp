// Where one frame sits in another, from tf2, waiting a bounded time: the one way the nodes bring an input given in
// some frame (a scan, a part file) into the frame they work in.
#pragma once
#include <ros/time.h>
#include <tf2_ros/buffer.h>

#include <Eigen/Geometry>
#include <string>

#include "rosmill/ros/namespaces.hpp"

namespace rosmill::edge {

// Whether tf has `source` in `target` at `stamp`, waiting up to `timeout_s` of wall time for it (tf2's own wait is
// on the ROS clock, which stops when a replayed bag ends: a scan waiting for a pose that never comes would wait
// for ever). `why` gets tf's reason when not.
bool can_transform_within(const tf2_ros::Buffer& buffer, const std::string& target, const std::string& source,
                          const ::ros::Time& stamp, double timeout_s, std::string* why);

// The transform taking `source` coordinates to `target` (metres), at `stamp` if tf has it within `timeout_s`, else
// the latest one (a scan stamped a little after the latest transform of a fixed sensor is still usable). Throws
// Error(where, "no transform to 'target' came within ... s (tf's reason)") when there is none.
Eigen::Isometry3d wait_for_transform(const tf2_ros::Buffer& buffer, const std::string& target,
                                     const std::string& source, const ::ros::Time& stamp, double timeout_s,
                                     const std::string& where);

}  // namespace rosmill::edge
