#include "rosmill/geometry/rigid_transform.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "rosmill/error.hpp"
#include "rosmill/geometry/placement.hpp"

namespace rosmill::core {

void check_rigid(const Eigen::Matrix4d& t, const std::string& where) {
  if (!t.allFinite()) throw Error(where, "the transform holds a NaN or infinite number");
  const Eigen::Matrix3d rot = t.topLeftCorner<3, 3>();
  const bool last_row = t.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-9);
  if (!last_row || !(rot.transpose() * rot).isIdentity(1e-6) || rot.determinant() < 0)
    throw Error(where, "the transform must be rigid (a rotation and a translation, no scale, shear or mirror)");
}

Eigen::Matrix4d rigid_from_xyz_quat(const Vec3& xyz, const Eigen::Vector4d& quat_xyzw, const std::string& where) {
  if (!xyz.allFinite() || !quat_xyzw.allFinite()) throw Error(where, "the pose holds a NaN or infinite number");
  const double norm = quat_xyzw.norm();
  if (std::abs(norm - 1.0) > 1e-3)
    throw Error(where, "the quaternion (x, y, z, w) must have norm 1, got " + std::to_string(norm));
  const Eigen::Quaterniond q(quat_xyzw[3] / norm, quat_xyzw[0] / norm, quat_xyzw[1] / norm, quat_xyzw[2] / norm);
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.topLeftCorner<3, 3>() = q.toRotationMatrix();
  t.topRightCorner<3, 1>() = xyz;
  return t;
}

void transform_points(const Eigen::Matrix4d& t, std::vector<Vec3>& points) {
  const Eigen::Matrix3d r = t.topLeftCorner<3, 3>();
  const Vec3 o = t.topRightCorner<3, 1>();
  for (Vec3& p : points) p = r * p + o;
}

std::vector<Vec3> transformed_points(const Eigen::Matrix4d& t, const std::vector<Vec3>& points) {
  std::vector<Vec3> out(points);
  transform_points(t, out);
  return out;
}

Eigen::Matrix4d rigid_inverse(const Eigen::Matrix4d& t) {
  Eigen::Matrix4d inv = Eigen::Matrix4d::Identity();
  const Eigen::Matrix3d rt = t.topLeftCorner<3, 3>().transpose();
  inv.topLeftCorner<3, 3>() = rt;
  inv.topRightCorner<3, 1>() = -(rt * t.topRightCorner<3, 1>());
  return inv;
}

double rotation_angle_deg(const Eigen::Matrix4d& t) {
  // From the trace, clamped: rounding may push it past +-1 for angles near 0 and 180 degrees.
  const double c = std::clamp((t.topLeftCorner<3, 3>().trace() - 1.0) / 2.0, -1.0, 1.0);
  // Near zero acos loses digits; the skew part gives the sine there.
  const Eigen::Matrix3d r = t.topLeftCorner<3, 3>();
  const double s = 0.5 * Vec3(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1)).norm();
  return std::atan2(s, c) * 180.0 / M_PI;
}

double translation_length(const Eigen::Matrix4d& t) { return t.topRightCorner<3, 1>().norm(); }

Mesh transformed_mesh(const Mesh& mesh, const Eigen::Matrix4d& t, const std::string& where) {
  check_rigid(t, where);
  return placed(mesh, Placement{"scan", "design", Eigen::Isometry3d(t)});
}

}  // namespace rosmill::core
