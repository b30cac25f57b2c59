#include "rosmill/testing/pose_error.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace rosmill::core::synthetic {

std::array<double, 6> error_by_dof(const scan::PoseInformation& info, const Eigen::Matrix4d& error) {
  const Eigen::Matrix3d r = error.topLeftCorner<3, 3>();
  const Vec3 slide = r * info.centre + error.topRightCorner<3, 1>() - info.centre;
  const Eigen::AngleAxisd turn(r);
  const Vec3 rotation = turn.axis() * turn.angle() * 180 / M_PI;
  std::array<double, 6> out{};
  for (size_t k = 0; k < 6; ++k) out[k] = info.dofs[k].axis.dot(info.dofs[k].rotation ? rotation : slide);
  return out;
}

double worst_sigma_ratio(const scan::PoseInformation& info, const Eigen::Matrix4d& error) {
  const std::array<double, 6> e = error_by_dof(info, error);
  double worst = 0;
  for (size_t k = 0; k < 6; ++k)
    if (std::isfinite(info.dofs[k].sigma)) worst = std::max(worst, std::abs(e[k]) / info.dofs[k].sigma);
  return worst;
}

}  // namespace rosmill::core::synthetic
