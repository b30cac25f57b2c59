// Batch drop-cutter over a regular XY grid: the `rosmill dropcutter` grid and the benchmark's.
#pragma once
#include <vector>

#include "rosmill/plan/surface.hpp"

namespace rosmill::core {

// Points x0 + i step, y0 + j step for i < nx, j < ny, row by row (y outer, x inner).
struct DropGrid {
  double x0 = 0, y0 = 0, step = 1;
  size_t nx = 0, ny = 0;
  size_t size() const { return nx * ny; }
  Vec2 point(size_t k) const { return Vec2(x0 + double(k % nx) * step, y0 + double(k / nx) * step); }
};

// The grid over a bounding box grown by the cutter radius: starts at (xmin - R, ymin - R),
// nx = floor((xmax + R - (xmin - R)) / step) + 1, ny likewise. Throws Error on a non-positive step.
DropGrid grid_over(const Box3& box, double radius, double step);

// Tip heights of the grid's points, never below `floor` (a cutter that touches nothing stays there).
std::vector<Vec3> drop_grid(const Surface& surface, const Cutter& cutter, const DropGrid& grid, double floor);

}  // namespace rosmill::core
