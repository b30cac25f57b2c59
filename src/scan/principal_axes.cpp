#include "rosmill/scan/principal_axes.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "rosmill/error.hpp"

namespace rosmill::core::scan {
namespace {

Eigen::Matrix4d pose(const Eigen::Matrix3d& rotation, const PrincipalFrame& design, const PrincipalFrame& scan) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.topLeftCorner<3, 3>() = rotation;
  t.topRightCorner<3, 1>() = scan.centroid - rotation * design.centroid;
  return t;
}

// The 24 proper rotations that map the coordinate axes onto signed coordinate axes.
std::vector<Eigen::Matrix3d> cube_rotations() {
  std::vector<Eigen::Matrix3d> out;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& perm : perms)
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
      for (int i = 0; i < 3; ++i) m(perm[i], i) = (signs >> i & 1) ? -1.0 : 1.0;
      if (m.determinant() > 0) out.push_back(m);
    }
  return out;
}

}  // namespace

PrincipalFrame principal_frame(const std::vector<Vec3>& points) {
  if (points.size() < 4) throw Error("principal axes", "at least 4 points are needed");
  PrincipalFrame f;
  for (const Vec3& p : points) f.centroid += p;
  f.centroid /= double(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points) cov += (p - f.centroid) * (p - f.centroid).transpose();
  cov /= double(points.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);  // increasing eigenvalues
  for (int i = 0; i < 3; ++i) {
    f.axes.col(i) = es.eigenvectors().col(2 - i);
    f.moments[i] = es.eigenvalues()[2 - i];
  }
  if (f.axes.determinant() < 0) f.axes.col(2) = -f.axes.col(2);
  return f;
}

int near_equal_moments(const Vec3& m, double tolerance) {
  const auto close = [&](double a, double b) { return std::abs(a - b) <= tolerance * std::max(a, b); };
  const bool first = close(m[0], m[1]), second = close(m[1], m[2]);
  if (first && second) return 3;
  return first || second ? 2 : 0;
}

std::vector<Eigen::Matrix4d> principal_axes_candidates(const PrincipalFrame& design, const PrincipalFrame& scan,
                                                       double tolerance, double step_deg) {
  std::vector<Eigen::Matrix3d> middles;  // rotations between the two principal frames
  const int equal = near_equal_moments(design.moments, tolerance);
  if (equal == 3) {
    middles = cube_rotations();
  } else {
    // The axis whose moment stands apart: the one free rotation is about it.
    const int apart = equal == 2 ? (std::abs(design.moments[0] - design.moments[1]) <=
                                            tolerance * design.moments[0] ? 2 : 0)
                                 : 0;
    const Vec3 axis = Vec3::Unit(apart), other = Vec3::Unit((apart + 1) % 3);
    const int steps = equal == 2 ? std::max(1, int(std::lround(360.0 / step_deg))) : 2;
    for (int turned = 0; turned < 2; ++turned)
      for (int s = 0; s < steps; ++s) {
        const double angle = 2 * M_PI * s / steps;
        Eigen::Matrix3d m = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
        if (turned) m = m * Eigen::AngleAxisd(M_PI, other).toRotationMatrix();
        middles.push_back(m);
      }
  }
  std::vector<Eigen::Matrix4d> out;
  out.reserve(middles.size());
  for (const Eigen::Matrix3d& m : middles) out.push_back(pose(scan.axes * m * design.axes.transpose(), design, scan));
  return out;
}

std::vector<Eigen::Matrix4d> principal_symmetry_probes(const Eigen::Matrix4d& pose, const PrincipalFrame& design,
                                                       double tolerance, double step_deg) {
  std::vector<Eigen::Matrix4d> out;
  // The candidates that map the design's frame onto itself are the rigid motions that keep its principal frame.
  for (const Eigen::Matrix4d& keep : principal_axes_candidates(design, design, tolerance, step_deg))
    if (!keep.topLeftCorner<3, 3>().isIdentity(1e-9)) out.push_back(pose * keep);
  return out;
}

}  // namespace rosmill::core::scan
