#include "rosmill/stock/design_height.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rosmill/stock/vertical_hits.hpp"

namespace rosmill::core::stock {

std::vector<float> design_heights(const Mesh& mesh, const GridSpec& g, double floor) {
  const float none = -std::numeric_limits<float>::infinity();
  std::vector<float> z(g.cells(), none);
  // A ray on a shared edge belongs to both triangles: the top has no gap along the edges.
  for_each_vertical_hit(mesh, g, Vec2::Zero(), -1e-9, [&](size_t c, double h, bool) {
    z[c] = std::max(z[c], static_cast<float>(h));
  });
  for (float& v : z)
    if (v == none) v = static_cast<float>(floor);
  return z;
}

std::vector<float> design_highest_in_cells(const Mesh& mesh, const GridSpec& g, double floor,
                                            std::vector<float> high) {
  GridSpec corners = g;
  corners.x0 -= 0.5 * g.cell;
  corners.y0 -= 0.5 * g.cell;
  corners.nx += 1;
  corners.ny += 1;
  const std::vector<float> at_corner = design_heights(mesh, corners, floor);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      float& h = high[g.index(i, j)];
      for (int v = j; v <= j + 1; ++v)
        for (int u = i; u <= i + 1; ++u) h = std::max(h, at_corner[corners.index(u, v)]);
    }
  return high;
}

std::vector<float> design_heights(const PointCloud& cloud, const GridSpec& g, int fill_cells) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> z(g.cells(), nan);
  for (const Vec3& p : cloud.points) {
    const int i = static_cast<int>(std::floor((p.x() - g.x0) / g.cell));
    const int j = static_cast<int>(std::floor((p.y() - g.y0) / g.cell));
    if (i < 0 || j < 0 || i >= g.nx || j >= g.ny) continue;
    float& cell = z[g.index(i, j)];
    if (std::isnan(cell) || p.z() > cell) cell = static_cast<float>(p.z());
  }
  // Fill gaps one ring at a time from the cells known before that ring.
  for (int ring = 0; ring < fill_cells; ++ring) {
    std::vector<float> next = z;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        if (!std::isnan(z[g.index(i, j)])) continue;
        float best = nan;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int u = i + di, v = j + dj;
            if (u < 0 || v < 0 || u >= g.nx || v >= g.ny) continue;
            const float n = z[g.index(u, v)];
            if (!std::isnan(n) && (std::isnan(best) || n > best)) best = n;
          }
        next[g.index(i, j)] = best;
      }
    z.swap(next);
  }
  return z;
}

}  // namespace rosmill::core::stock
