#include "rosmill/ros/transform_wait.hpp"

#include <tf2_eigen/tf2_eigen.h>

#include "rosmill/error.hpp"

namespace rosmill::edge {

bool can_transform_within(const tf2_ros::Buffer& buffer, const std::string& target, const std::string& source,
                          const ::ros::Time& stamp, double timeout_s, std::string* why) {
  const ::ros::WallTime end = ::ros::WallTime::now() + ::ros::WallDuration(timeout_s);
  while (true) {
    if (buffer.canTransform(target, source, stamp, why)) return true;
    if (!::ros::ok() || ::ros::WallTime::now() >= end) return false;
    ::ros::WallDuration(0.005).sleep();
  }
}

Eigen::Isometry3d wait_for_transform(const tf2_ros::Buffer& buffer, const std::string& target,
                                     const std::string& source, const ::ros::Time& stamp, double timeout_s,
                                     const std::string& where) {
  std::string why;
  if (can_transform_within(buffer, target, source, stamp, timeout_s, &why))
    return tf2::transformToEigen(buffer.lookupTransform(target, source, stamp));
  if (!stamp.isZero() && buffer.canTransform(target, source, ::ros::Time(0), &why))
    return tf2::transformToEigen(buffer.lookupTransform(target, source, ::ros::Time(0)));
  throw Error(where, "no transform to '" + target + "' came within " + std::to_string(timeout_s) + " s (" + why + ")");
}

}  // namespace rosmill::edge
