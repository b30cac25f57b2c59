// Waterline (z-level finishing): at each height (every step-down, every flat face and the floor), the closed
// cutter-location loops that bound where the cutter would go into the part. The CL heights are dropped once on a
// grid; each level's loops are the iso-contour of that grid (marching squares, saddles decided by the cell centre),
// their vertices placed exactly on the contour by bisection and refined until every chord is within the tolerance.
// The grid covers the part, the cutter and what the surface says reaches further (Surface::held_reach: a holder
// wider than the cutter). Bisection only asks whether the cutter is held above the level (Surface::held_above,
// through a probe focused on each edge and chord), which a mesh answers without the exact drop: the same answers,
// far fewer triangles opened. A point counts as material only when its CL height is above the level by more than
// 1e-6 mm, so a level at the height of a flat face gives the loops around what stands above it, not noise on the
// face.
#pragma once
#include <memory>
#include <vector>

#include "rosmill/plan/plan_support.hpp"

namespace rosmill::core {

struct WaterlineOptions {
  std::vector<double> levels;  // heights of the tip; empty: from the top down every step-down
};

// Loops of one level in CL coordinates (closed: the last point is not repeated).
using Loop = std::vector<Vec3>;

// A contour of one level: its points in order, and whether the last joins the first. An open one runs off the
// grid (what holds the cutter there reaches beyond it: a fixture beside the part), or was broken at a chord no
// point of which near its middle is clear; the cutter follows it and lifts at its ends.
struct WallContour {
  Loop points;
  bool closed = true;
};

// A part's walls level by level over one grid of dropped CL heights: the drops made once, then the loops of any
// levels asked for, each call's levels on both cores. Adaptive clearing asks for its first level alone and for
// the others while it plans the first.
class WaterlineWalls {
 public:
  // Checks the work (the grid and `levels` levels, 0: one every step-down) against the plan's bounds; drops the
  // grid.
  WaterlineWalls(const Surface& surface, const PlanParams& params, size_t levels, const PlanProgress& progress = {});
  ~WaterlineWalls();
  // The contours of each level, in the order given; progress reported from `from` to `to`.
  std::vector<std::vector<WallContour>> contours(const std::vector<double>& levels, const PlanProgress& progress = {},
                                             double from = 0, double to = 1) const;
  // Their points alone (an open contour too, as if it closed: for what fills the loops as polygons).
  std::vector<std::vector<Loop>> loops(const std::vector<double>& levels, const PlanProgress& progress = {},
                                       double from = 0, double to = 1) const;
  // A level every step-down below the highest CL height, at every flat face and at the part's floor (each plus the
  // allowance).
  std::vector<double> default_levels() const;
  const PlanFrame& frame() const { return f_; }

 private:
  struct Grid;
  const Surface& surface_;
  PlanFrame f_;
  std::unique_ptr<const Grid> grid_;
};

Job waterline_on(const Surface& surface, const PlanParams& params, const WaterlineOptions& options,
                 const PlanProgress& progress = {}, std::vector<std::vector<Loop>>* loops_out = nullptr);
Job waterline_strategy(const Surface& surface, const PlanParams& params, const PlanProgress& progress);

}  // namespace rosmill::core
