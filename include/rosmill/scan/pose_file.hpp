// A sensor pose in a small YAML file: where a view's points are in the common frame (the view frame -> the
// fused frame), for `rosmill fuse`. Either form, with the translation in `units` (default m, as clouds are):
//
//   units: m                           # mm | inch | m
//   matrix: [r00, r01, r02, tx,  r10, r11, r12, ty,  r20, r21, r22, tz,  0, 0, 0, 1]   # 4x4, row-major
//
//   units: m
//   xyz: [x, y, z]
//   quaternion: [qx, qy, qz, qw]       # unit quaternion, ROS order (x, y, z, w)
#pragma once
#include <string>

#include <Eigen/Core>

namespace rosmill::core::scan {

// The pose in millimetres. Throws Error naming the file (and the field) on any bad content: neither or both
// forms, a wrong count, a non-number, NaN, a matrix that is not rigid, a quaternion that is not unit.
Eigen::Matrix4d read_pose_file(const std::string& path);
// The same from YAML text; `name` is used in errors.
Eigen::Matrix4d parse_pose(const std::string& text, const std::string& name);

}  // namespace rosmill::core::scan
