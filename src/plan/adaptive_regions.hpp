// The regions of one adaptive level, in XY: where the cutter's centre may go (out of the part grown by the
// allowance, and of the fixture), the material standing above the level, and what of it the cutter can reach.
#pragma once
#include <vector>

#include "rosmill/geometry/clip_region.hpp"
#include "rosmill/plan/plan_support.hpp"
#include "rosmill/plan/waterline.hpp"

namespace rosmill::core {

struct LevelRegions {
  clip::Paths allowed;   // centres whose cutter stays out of the part (and fixture) at and above the level
  clip::Paths material;  // material standing above the level
  clip::Paths target;    // the material the cutter reaches: material within R - skin of `allowed`
};

// `loops`: the waterline's loops at the level (closed, around where the cutter would go into the part);
// `work_lo`, `work_hi`: the rectangle the centre keeps to; `arc_tolerance`: of the offsets; `skin`: how much
// less than R from the allowed centres the target reaches.
LevelRegions level_regions(const PlanParams& params, const PlanFrame& f, double z, const std::vector<Loop>& loops,
                           const Vec2& work_lo, const Vec2& work_hi, double arc_tolerance, double skin);

}  // namespace rosmill::core
