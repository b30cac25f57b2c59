// Holes in a scan: cells of a plan-view grid that hold no point.
//
// Empty cells connected to the grid's border are outside the part (Muslimin et al.'s "free boundary": the cutter may
// go down there). Empty cells enclosed by data are missing data (occlusion, a dark or shiny spot): the cutter
// must never plunge into them. Policy (stated, and reported per hole):
//   Bridge (default, conservative): the hole is covered by a flat lid at the height of the highest point in the
//          cells around it, so the cutter stays at least at the highest neighbour's height over the hole.
//   Skip:  as Bridge for the drop-cutter, and the cloud strategies leave out every cutter location whose
//          footprint reaches the hole (the tool retracts over it).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rosmill/cloud/cloud_grid.hpp"

namespace rosmill::core {

// The default hole-detection cell: kHoleCellRadii x the cloud's median empty-circle radius (sampling_radius at
// q = 0.5, measured by area so that dense parts do not hide sparse ones). On a randomly sampled surface a cell of
// 8 median radii holds about 14 points (an empty one has odds ~ e^-14), on a square grid at least 9, so an
// enclosed empty cell is missing data, not the gap between two ordinary points. A cloud too thin for the
// measure falls back on 3.5 x the 95th percentile of the nearest-neighbour distance.
constexpr double kHoleCellRadii = 8.0;
double auto_hole_cell(const CloudGrid& grid);

enum class HolePolicy { Bridge, Skip };
// "bridge" or "skip"; throws Error naming `where` otherwise.
HolePolicy parse_hole_policy(const std::string& text, const std::string& where = "hole policy");

struct Hole {
  Box3 box;            // plan-view extent of its cells (z: the lid height in both min and max)
  size_t cells = 0;
  double area = 0.0;   // mm²
  double lid_z = 0.0;  // highest point in the cells around the hole
};

// The hole map of a cloud: a grid (its own cell size, coarser than the point spacing) whose enclosed empty
// cells carry a lid height.
class HoleMap {
 public:
  HoleMap() = default;
  // `cell` is the hole-detection cell (mm): it must be a few times the point spacing, or the gaps between
  // ordinary neighbouring points would count as holes (see auto_hole_cell).
  HoleMap(const std::vector<Vec3>& points, double cell);

  bool any() const { return !holes_.empty(); }
  const std::vector<Hole>& holes() const { return holes_; }
  size_t empty_cells() const { return empty_cells_; }      // all empty cells, outside ones included
  size_t outside_cells() const { return outside_cells_; }  // empty and connected to the border
  size_t cells() const { return size_t(grid_.nx()) * size_t(grid_.ny()); }
  const CloudGrid& grid() const { return grid_; }
  // Lid height of a cell, or NaN when the cell is not part of a hole.
  double lid(size_t cell) const { return lid_.empty() ? NAN : lid_[cell]; }
  // True when a disc of radius r at (x, y) overlaps any hole cell.
  bool disc_touches_hole(double x, double y, double r) const;

 private:
  CloudGrid grid_;
  std::vector<double> lid_;  // per cell; NaN when not a hole
  std::vector<Hole> holes_;
  size_t empty_cells_ = 0, outside_cells_ = 0;
};

}  // namespace rosmill::core
