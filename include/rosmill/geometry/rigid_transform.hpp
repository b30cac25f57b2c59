// Rigid transforms as 4x4 homogeneous matrices (millimetres), without tf: checked, applied, inverted, measured.
// Scans arrive with sensor poses and leave registration as a pose; every such matrix passes check_rigid() first.
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

// Throws Error(where) unless `t` is finite, has the last row 0 0 0 1 and a proper rotation (orthonormal within
// 1e-6, determinant +1: no scale, shear or mirror).
void check_rigid(const Eigen::Matrix4d& t, const std::string& where);

// The pose of a translation and a unit quaternion (x, y, z, w). Throws Error(where) on a non-finite number or a
// quaternion whose norm is not 1 within 1e-3 (a typo, not rounding); a norm within that is normalised.
Eigen::Matrix4d rigid_from_xyz_quat(const Vec3& xyz, const Eigen::Vector4d& quat_xyzw, const std::string& where);

void transform_points(const Eigen::Matrix4d& t, std::vector<Vec3>& points);
std::vector<Vec3> transformed_points(const Eigen::Matrix4d& t, const std::vector<Vec3>& points);
// The mesh moved by `t` (checked rigid first: Error(where)): the same faces over moved vertices, a rigid motion
// keeps the welding; normals, areas and box recomputed.
Mesh transformed_mesh(const Mesh& mesh, const Eigen::Matrix4d& t, const std::string& where);
// The inverse of a rigid transform (transpose of the rotation; no general matrix inverse).
Eigen::Matrix4d rigid_inverse(const Eigen::Matrix4d& t);

// The angle of the rotation part, degrees in [0, 180].
double rotation_angle_deg(const Eigen::Matrix4d& t);
// The translation part's length, millimetres.
double translation_length(const Eigen::Matrix4d& t);

}  // namespace rosmill::core
