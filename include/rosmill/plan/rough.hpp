// Roughing: z-level area clearing from the stock's top down in step-downs, leaving the allowance. Each level is
// cut in zigzag lines over the stock box, only where the cutter fits: a line is sampled once with the cutter
// widened by half the sample spacing, so a sample that is free at a level proves the real cutter free within
// that half spacing either side, and the cut pieces are exactly the union of those proven-free spans. A piece
// is entered from above the level just cleared and ramps down into the material along itself. With a stock mesh
// (PlanParams::stock_mesh) the pieces are further kept to where the cutter reaches the stock's material at that
// level (plan/stock.hpp), so air the box would have cut is left alone; a piece that starts where the cutter
// enters the stock's reach from outside goes straight down there, in air, instead of ramping. With a job's
// material (PlanParams::material, material_top.hpp) the levels start at the material's own top, a piece is kept
// to where the cutter meets material above its level (gaps of air up to PlanParams::air_gap bridged, so no feed
// runs through more air than that), and the cutter goes from piece to piece by rapids just over the material it
// passes (link_clearance above the highest within reach of the whole link, the material lowered as the levels
// cut it) instead of the safe height.
#pragma once
#include "rosmill/plan/plan_support.hpp"

namespace rosmill::core {

struct RoughOptions {
  double ramp_slope = 0.1;  // descent per unit of horizontal travel while ramping in (about 6 degrees)
};

Job rough_on(const Surface& surface, const PlanParams& params, const RoughOptions& options,
             const PlanProgress& progress = {});
Job rough_strategy(const Surface& surface, const PlanParams& params, const PlanProgress& progress);

}  // namespace rosmill::core
