#include "rosmill/verify/design_height.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rosmill::core::verify {

std::vector<float> design_heights(const Mesh& mesh, const GridSpec& g, double floor) {
  const float none = -std::numeric_limits<float>::infinity();
  std::vector<float> z(g.cells(), none);
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const Vec3 &a = mesh.corner(f, 0), &b = mesh.corner(f, 1), &c = mesh.corner(f, 2);
    const double area2 = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(area2) < 1e-12) continue;  // vertical (or degenerate): a vertical ray does not hit its inside
    const int i0 = g.first_x(std::min({a.x(), b.x(), c.x()})), i1 = g.last_x(std::max({a.x(), b.x(), c.x()}));
    const int j0 = g.first_y(std::min({a.y(), b.y(), c.y()})), j1 = g.last_y(std::max({a.y(), b.y(), c.y()}));
    const double inv = 1.0 / area2, eps = -1e-9;  // a ray on a shared edge belongs to both triangles
    for (int j = j0; j <= j1; ++j) {
      const double y = g.cy(j);
      for (int i = i0; i <= i1; ++i) {
        const double x = g.cx(i);
        // Barycentric weights of (x, y) in the triangle's XY projection.
        const double wa = ((b.x() - x) * (c.y() - y) - (c.x() - x) * (b.y() - y)) * inv;
        const double wb = ((c.x() - x) * (a.y() - y) - (a.x() - x) * (c.y() - y)) * inv;
        const double wc = 1.0 - wa - wb;
        if (wa < eps || wb < eps || wc < eps) continue;
        float& cell = z[g.index(i, j)];
        cell = std::max(cell, static_cast<float>(wa * a.z() + wb * b.z() + wc * c.z()));
      }
    }
  }
  for (float& v : z)
    if (v == none) v = static_cast<float>(floor);
  return z;
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

}  // namespace rosmill::core::verify
