// A rigid placement between two named frames (REP 105 style, as tf names them): the pose of frame `child` in frame
// `parent`, so that a point given in `child` coordinates is `pose * p` in `parent` coordinates (millimetres).
// Every frame change in the core is one of these: the workpiece in a setup's frame, a setup's frame on the
// machine, a fixture in a setup. Composing two checks that they meet in a common frame, so a placement cannot be
// applied to coordinates of the wrong frame without saying so; a part, a cloud or a box is moved in one place
// (placed() below), whoever asks.
#pragma once
#include <string>

#include <Eigen/Geometry>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

struct Placement {
  std::string parent = "parent", child = "child";
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();

  Vec3 point(const Vec3& p) const { return pose * p; }                       // child -> parent
  Vec3 direction(const Vec3& d) const { return pose.linear() * d; }          // child -> parent, no translation
  Vec3 point_back(const Vec3& p) const { return pose.linear().transpose() * (p - pose.translation()); }
  Vec3 direction_back(const Vec3& d) const { return pose.linear().transpose() * d; }
  Eigen::Quaterniond rotation() const { return Eigen::Quaterniond(pose.linear()); }
  Vec3 translation() const { return pose.translation(); }
  bool identity(double tolerance = 1e-12) const;
  // The same placement seen the other way: `parent` in `child`.
  Placement inverse() const;
};

// The placement of `inner.child` in `outer.parent`; throws Error(where) unless inner.parent is outer.child.
Placement compose(const Placement& outer, const Placement& inner, const std::string& where = "frames");

// A placement from a rotation and a translation (p_parent = rotation * p_child + translation).
Placement placement_of(const std::string& parent, const std::string& child, const Eigen::Quaterniond& rotation,
                       const Vec3& translation = Vec3::Zero());

// Throws Error(where) unless the pose is finite and a proper rotation (orthonormal within 1e-6, determinant +1).
void check_placement(const Placement& placement, const std::string& where);

// The mesh, cloud or box given in `placement.child` coordinates, in `placement.parent` coordinates. A mesh keeps its
// faces and welding (a rigid motion changes neither); normals, areas and bounds are recomputed. A box gives the
// bounds of its eight corners moved.
Mesh placed(const Mesh& mesh, const Placement& placement);
PointCloud placed(const PointCloud& cloud, const Placement& placement);
Box3 placed(const Box3& box, const Placement& placement);

}  // namespace rosmill::core
