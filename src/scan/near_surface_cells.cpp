#include "rosmill/scan/near_surface_cells.hpp"

#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::core::scan {

NearSurfaceCells::NearSurfaceCells(const std::vector<Vec3>& points, const Box3& box, double cell) : cell_(cell) {
  if (!(cell > 0) || box.empty()) throw Error("near-surface cells", "a positive cell and a box are needed");
  origin_ = box.min - Vec3::Constant(2 * cell);
  for (int a = 0; a < 3; ++a) size_[a] = int(std::ceil((box.max[a] - box.min[a]) / cell)) + 5;
  marked_.assign(size_t(size_[0]) * size_[1] * size_[2], 0);
  for (const Vec3& p : points) {
    const Eigen::Vector3i c = cell_of(p);
    for (int a = 0; a < 3; ++a)
      if (c[a] < 1 || c[a] >= size_[a] - 1) throw Error("near-surface cells", "a point lies outside the box");
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) marked_[index(c + Eigen::Vector3i(dx, dy, dz))] = 1;
  }
}

Eigen::Vector3i NearSurfaceCells::cell_of(const Vec3& p) const {
  const Vec3 u = (p - origin_) / cell_;
  // Far outside the grid, or not a number: a cell outside it (the cast to int would be undefined).
  for (int a = 0; a < 3; ++a)
    if (!(std::abs(u[a]) < 1e9)) return Eigen::Vector3i(-1, -1, -1);
  return Eigen::Vector3i(int(std::floor(u.x())), int(std::floor(u.y())), int(std::floor(u.z())));
}

bool NearSurfaceCells::near(const Vec3& p) const {
  const Eigen::Vector3i c = cell_of(p);
  for (int a = 0; a < 3; ++a)
    if (c[a] < 0 || c[a] >= size_[a]) return false;
  return marked_[index(c)] != 0;
}

double NearSurfaceCells::share_near(const std::vector<Vec3>& points, const Eigen::Matrix4d& motion) const {
  if (points.empty()) return 0;
  const Eigen::Matrix3d r = motion.topLeftCorner<3, 3>();
  const Vec3 t = motion.topRightCorner<3, 1>();
  size_t near_count = 0;
  for (const Vec3& p : points) near_count += near(r * p + t);
  return double(near_count) / double(points.size());
}

}  // namespace rosmill::core::scan
