// Raster finishing: parallel lines at a stepover and an angle, each sampled adaptively on the surface until
// every chord is within the tolerance, linked zigzag along the surface or cut one way with safe retracts,
// optionally only inside a boundary polygon, leaving the allowance.
#pragma once
#include <vector>

#include "rosmill/plan/plan_support.hpp"

namespace rosmill {

struct RasterOptions {
  bool zigzag = true;  // false: every line in the same direction, retracting between lines
  Region boundary;     // where the cutter axis may go (region.hpp); empty: the part's box grown by the radius
};

Job raster_on(const Surface& surface, const PlanParams& params, const RasterOptions& options,
              const PlanProgress& progress = {});
// The strategy table's form (zigzag, no boundary).
Job raster_strategy(const Surface& surface, const PlanParams& params, const PlanProgress& progress);

// Drops points that lie on the straight line of their neighbours (within 1e-9 mm): same path, fewer moves.
void drop_collinear(std::vector<Vec3>& points);

}  // namespace rosmill
