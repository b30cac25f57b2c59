#include "rosmill/stock/scanned_top.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace rosmill::core::stock {
namespace {

constexpr size_t kOutside = std::numeric_limits<size_t>::max();

// Least squares of the plane z = a + b x + c y over points, in coordinates relative to a cell's centre and in
// cell units (a well-scaled system).
struct PlaneFit {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  size_t points = 0;
  double lo = INFINITY, hi = -INFINITY;

  void add(const Vec3& p, double cx, double cy, double cell) {
    const Eigen::Vector3d row(1.0, (p.x() - cx) / cell, (p.y() - cy) / cell);
    normal += row * row.transpose();
    rhs += row * p.z();
    ++points;
    lo = std::min(lo, p.z());
    hi = std::max(hi, p.z());
  }
  // The plane at the centre, or NaN when the points do not fix it (fewer than three, or along a line: a pivot of
  // the normal equations this small against the point count leaves the slope free along some direction).
  double at_centre() const {
    if (points < 3) return NAN;
    const Eigen::LDLT<Eigen::Matrix3d> solve(normal);
    if (solve.info() != Eigen::Success || solve.vectorD().minCoeff() < 1e-3 * double(points)) return NAN;
    return solve.solve(rhs)(0);
  }
};

}  // namespace

std::vector<float> scanned_top(const PointCloud& cloud, const GridSpec& g) {
  // The points grouped by cell (a counting sort: one pass to count, one to place).
  std::vector<size_t> cell_of(cloud.points.size(), kOutside);
  std::vector<size_t> first(g.cells() + 1, 0);
  for (size_t k = 0; k < cloud.points.size(); ++k) {
    const Vec3& p = cloud.points[k];
    // A point on the grid's far edge (the cloud's own bounds make the grid: its highest x and y lie there) is in
    // the last cell, not off the grid.
    const auto index = [](double u, int n) { return u >= n && u <= n + 1e-9 ? n - 1.0 : std::floor(u); };
    const double fi = index((p.x() - g.x0) / g.cell, g.nx), fj = index((p.y() - g.y0) / g.cell, g.ny);
    if (!(fi >= 0 && fj >= 0 && fi < g.nx && fj < g.ny)) continue;
    cell_of[k] = g.index(static_cast<int>(fi), static_cast<int>(fj));
    ++first[cell_of[k] + 1];
  }
  for (size_t c = 0; c < g.cells(); ++c) first[c + 1] += first[c];
  std::vector<size_t> order(first.back());
  std::vector<size_t> next(first.begin(), first.end() - 1);
  for (size_t k = 0; k < cell_of.size(); ++k)
    if (cell_of[k] != kOutside) order[next[cell_of[k]]++] = k;

  // Each cell that holds points: the plane through its own and its eight neighbours' points (a 3 x 3 window:
  // enough points for a plane where a scan is sparse, and flat enough that a curved surface bends away from it by
  // well under the scan's noise), read at the centre and kept within the window's heights.
  std::vector<float> top(g.cells(), std::numeric_limits<float>::quiet_NaN());
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const size_t c = g.index(i, j);
      if (first[c] == first[c + 1]) continue;
      PlaneFit fit;
      for (int v = std::max(0, j - 1); v <= std::min(g.ny - 1, j + 1); ++v)
        for (int u = std::max(0, i - 1); u <= std::min(g.nx - 1, i + 1); ++u) {
          const size_t n = g.index(u, v);
          for (size_t k = first[n]; k < first[n + 1]; ++k) fit.add(cloud.points[order[k]], g.cx(i), g.cy(j), g.cell);
        }
      const double z = fit.at_centre();
      top[c] = static_cast<float>(std::isnan(z) ? fit.hi : std::clamp(z, fit.lo, fit.hi));
    }
  return top;
}

}  // namespace rosmill::core::stock
