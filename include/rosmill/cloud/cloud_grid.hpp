// A uniform 2-D grid over the XY footprint of a point cloud, points sorted into cells (CSR layout).
//
// The drop-cutter's query is "every point within R of (x, y) in plan view": a fixed-radius disc in 2-D. A flat
// grid answers it by visiting the few cells under the disc's square and scanning contiguous memory, with no
// tree descent and no allocation; a kd-tree is slower for this query shape.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

struct GridPoint {
  double x, y, z;
};

class CloudGrid {
 public:
  CloudGrid() = default;
  // Sorts `points` (finite, millimetres) into square cells of `cell` mm over their XY bounding box. The cell
  // is grown when the grid would exceed `max_cells` cells.
  CloudGrid(const std::vector<Vec3>& points, double cell, size_t max_cells = size_t(1) << 24);

  double cell() const { return cell_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double x0() const { return x0_; }
  double y0() const { return y0_; }
  size_t size() const { return points_.size(); }
  const Box3& bounds() const { return bounds_; }

  // Cell column/row of a coordinate, clamped to the grid (inline: every drop and sweep asks for a few).
  int col(double x) const { return int(std::clamp(std::floor((x - x0_) / cell_), 0.0, double(nx_ - 1))); }
  int row(double y) const { return int(std::clamp(std::floor((y - y0_) / cell_), 0.0, double(ny_ - 1))); }
  size_t index(int c, int r) const { return size_t(r) * size_t(nx_) + size_t(c); }
  // Squared plan distance from (x, y) to the rectangle of cell (c, r); 0 inside it.
  double distance2(int c, int r, double x, double y) const {
    const double lx = x0_ + c * cell_, ly = y0_ + r * cell_;
    const double dx = std::max(std::max(lx - x, 0.0), x - (lx + cell_));
    const double dy = std::max(std::max(ly - y, 0.0), y - (ly + cell_));
    return dx * dx + dy * dy;
  }
  // Points of one cell, contiguous.
  const GridPoint* begin(size_t cell) const { return points_.data() + start_[cell]; }
  const GridPoint* end(size_t cell) const { return points_.data() + start_[cell + 1]; }
  uint32_t count(size_t cell) const { return start_[cell + 1] - start_[cell]; }
  // Highest z in a cell (-inf when empty): lets a query skip cells that cannot raise the cutter.
  double zmax(size_t cell) const { return zmax_[cell]; }
  const std::vector<GridPoint>& points() const { return points_; }
  // The same points in cells of another size.
  CloudGrid regridded(double cell) const;

 private:
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 0, ny_ = 0;
  Box3 bounds_;
  std::vector<uint32_t> start_;  // nx*ny + 1 offsets into points_
  std::vector<GridPoint> points_;
  std::vector<double> zmax_;
};

// A cell size that puts a few points in each cell of a cloud of `n` points covering `xy_area` mm².
double auto_grid_cell(size_t n, double xy_area);

// Mean distance from a point to its nearest neighbour (3-D), estimated on up to `samples` points spread
// evenly through the cloud; 0 for fewer than two points.
double mean_spacing(const CloudGrid& grid, size_t samples = 20000);
// The q-quantile (0..1) of the same nearest-neighbour distances: the spacing in the sparse parts of a cloud
// whose density varies (the hole-detection cell is sized on it).
double spacing_quantile(const CloudGrid& grid, double q, size_t samples = 20000);

// The cloud's sampling radius in plan view: the q-quantile of the plan distance from a position on the scanned
// surface to its nearest point (the radius of the empty circle there), probed at `samples` positions spread
// evenly over the `coarse` cells that hold points and whose eight neighbours hold points too (inside the data:
// no border, no hole). Probes spread by area, not by point, so dense parts of a cloud do not hide its sparse
// ones. On a square grid of pitch p it is about 0.4 p at q = 0.5 and 0.6 p at q = 0.95 (the largest empty circle
// has radius p/sqrt 2); on random samples of density λ about 0.47/sqrt(λ) at q = 0.5. 0 when no cell qualifies.
double sampling_radius(const CloudGrid& grid, const CloudGrid& coarse, double q = 0.95, size_t samples = 8000);

}  // namespace rosmill::core
