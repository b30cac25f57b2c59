// Grid-method roughing (Muslimin et al., "Direct NC Toolpath Generation from 3D Point Cloud Datasets", 3.3.1),
// on any Surface: zigzag lines in x, 2R - 0.5δ apart from y_min + 0.5δ (δ the allowance; or the stepover when
// given), from x_min - R - δ to x_max + R + δ (entry from the free boundary); levels z_max - d, z_max - 2d, ...
// down to the floor (d the step-down). At every sample the cutter goes to max(level, T), T the drop of the
// cutter grown by δ and lifted by δ; between samples it moves up first or down last (a staircase), and the
// samples are close enough that the footprints of two neighbours cover the band swept between them: no straight
// move comes closer than δ to the surface. Stretches where a level cuts nothing new are crossed at the safe
// height, and samples where the surface skips (Surface::skips) are left out. The stock is the part's box (the
// stock margin is not used): the safe height is the safe clearance above its top.
#pragma once
#include "rosmill/plan/plan_report.hpp"
#include "rosmill/plan/plan_support.hpp"

namespace rosmill::core {

Job grid_rough_on(const Surface& surface, const PlanParams& params, const PlanProgress& progress = {},
                  PlanReport* report = nullptr);

}  // namespace rosmill::core
