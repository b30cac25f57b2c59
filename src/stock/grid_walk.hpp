// The cells of a grid a straight line crosses, in order (Amanatides & Woo, "A fast voxel traversal algorithm for
// ray tracing", Eurographics 1987, in two dimensions).
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "rosmill/stock/height_field.hpp"

namespace rosmill::core::stock {

// Calls fn(i, j, ta, tb) for every cell of g that the line o + t d (d not zero) crosses for t in [t0, t1], with the
// part [ta, tb] of t inside the cell, in increasing t. Cells are the closed squares of the grid's lattice.
template <class Fn>
void walk_cells(const GridSpec& g, const Vec2& o, const Vec2& d, double t0, double t1, Fn&& fn) {
  const double inf = std::numeric_limits<double>::infinity();
  const double lo[2] = {g.x0, g.y0}, hi[2] = {g.x0 + g.nx * g.cell, g.y0 + g.ny * g.cell};
  for (int a = 0; a < 2; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return;
      continue;
    }
    const double p = (lo[a] - o[a]) / d[a], q = (hi[a] - o[a]) / d[a];
    t0 = std::max(t0, std::min(p, q));
    t1 = std::min(t1, std::max(p, q));
  }
  if (!(t0 < t1)) return;
  const Vec2 start = o + 0.5 * (t0 + std::min(t1, t0 + 1e-6 * g.cell / d.norm())) * d;
  int i = std::clamp(static_cast<int>(std::floor((start.x() - g.x0) / g.cell)), 0, g.nx - 1);
  int j = std::clamp(static_cast<int>(std::floor((start.y() - g.y0) / g.cell)), 0, g.ny - 1);
  const int si = d.x() > 0 ? 1 : -1, sj = d.y() > 0 ? 1 : -1;
  double next_x = d.x() != 0 ? (g.x0 + (i + (d.x() > 0)) * g.cell - o.x()) / d.x() : inf;
  double next_y = d.y() != 0 ? (g.y0 + (j + (d.y() > 0)) * g.cell - o.y()) / d.y() : inf;
  const double step_x = d.x() != 0 ? g.cell / std::abs(d.x()) : inf;
  const double step_y = d.y() != 0 ? g.cell / std::abs(d.y()) : inf;
  double t = t0;
  while (t < t1) {
    const double tb = std::min({next_x, next_y, t1});
    if (tb > t) fn(i, j, t, tb);
    if (tb >= t1) return;
    if (next_x <= next_y) {
      i += si;
      next_x += step_x;
    } else {
      j += sj;
      next_y += step_y;
    }
    if (i < 0 || j < 0 || i >= g.nx || j >= g.ny) return;
    t = tb;
  }
}

}  // namespace rosmill::core::stock
