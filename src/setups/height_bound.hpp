// A conservative top view of a mesh, for answering most "does anything stand above z near (x, y)?" questions of the
// reach analysis without an exact drop: per cell of a square grid, a height no lower than the highest the mesh
// reaches over the cell (each triangle's plane at the cell's corners, within the triangle's own heights, over the
// cells of its box), and the same grown to the highest over a square of cells around each (a disc of a radius lies
// within the square of its cells, whatever point of the centre cell it is centred on). A question the bound answers
// "nothing" is answered; any other goes to the exact drop. Private to the setups area.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core::setups {

class HeightBound {
 public:
  // Over the mesh's XY bounds grown by `margin` (at least the largest radius grown() will be asked for), in square
  // cells of `cell` mm.
  HeightBound(const Mesh& mesh, double cell, double margin);

  // The bound grown to cover a disc of `radius` (at most the margin) around any point of a cell: an upper bound of
  // the highest point of the mesh within `radius` of any point of each cell (-infinity where none can be).
  std::vector<float> grown(double radius) const;
  // The value of `map` (the bound or a grown one) at (x, y); -infinity outside the grid, farther than the margin
  // from the mesh.
  float at(const std::vector<float>& map, double x, double y) const {
    const double i = std::floor((x - x0_) / cell_), j = std::floor((y - y0_) / cell_);
    if (!(i >= 0 && j >= 0 && i < nx_ && j < ny_)) return -INFINITY;
    return map[static_cast<size_t>(j) * nx_ + static_cast<size_t>(i)];
  }

 private:
  void add_triangle(const Vec3& a, const Vec3& b, const Vec3& c);
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<float> top_;
};

}  // namespace rosmill::core::setups
