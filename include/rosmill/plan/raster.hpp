// Raster finishing: parallel lines at a stepover and an angle, each sampled on the surface by the plan's sampling
// policy (PlanParams::sampling: chord refinement until every chord is within the tolerance, or the step-error
// interpolation with every move checked against the surface, step_error.hpp), linked zigzag along the surface or
// cut one way with safe retracts, optionally only inside a boundary polygon, leaving the allowance. Positions
// where the surface skips (a cloud's holes under the Skip policy) are left out: the cut stops and retracts.
#pragma once
#include <vector>

#include "rosmill/plan/plan_report.hpp"
#include "rosmill/plan/plan_support.hpp"

namespace rosmill::core {

struct RasterOptions {
  bool zigzag = true;  // false: every line in the same direction, retracting between lines
  Region boundary;     // where the cutter axis may go (region.hpp); empty: the part's box grown by the radius
  PlanReport* report = nullptr;  // when given: filled with the lines, samples and inserted locations
};

Job raster_on(const Surface& surface, const PlanParams& params, const RasterOptions& options,
              const PlanProgress& progress = {});

}  // namespace rosmill::core
