// Waterline (z-level finishing): at each height, the closed cutter-location loops that bound where the cutter
// would go into the part. The CL heights are dropped once on a grid; each level's loops are the iso-contour of
// that grid (marching squares, saddles decided by the cell centre), their vertices placed exactly on the
// contour by bisection and refined until every chord is within the tolerance. Bisection only asks whether the
// cutter is held above the level (Surface::held_above, through a probe focused on each edge and chord), which a
// mesh answers without the exact drop: the same answers, far fewer triangles opened. A point
// counts as material only when its CL height is above the level by more than 1e-6 mm, so a level at the height
// of a flat face gives the loops around what stands above it, not noise on the face.
#pragma once
#include <vector>

#include "rosmill/plan/plan_support.hpp"

namespace rosmill::core {

struct WaterlineOptions {
  std::vector<double> levels;  // heights of the tip; empty: from the top down every step-down
};

// Loops of one level in CL coordinates (closed: the last point is not repeated).
using Loop = std::vector<Vec3>;

Job waterline_on(const Surface& surface, const PlanParams& params, const WaterlineOptions& options,
                 const PlanProgress& progress = {}, std::vector<std::vector<Loop>>* loops_out = nullptr);
Job waterline_strategy(const Surface& surface, const PlanParams& params, const PlanProgress& progress);

}  // namespace rosmill::core
