#include "rosmill/plan/plan_params.hpp"

#include <cmath>

#include "rosmill/value_range.hpp"

namespace rosmill::core {

void check_plan_params(const PlanParams& p) {
  check_tool(p.tool, "parameter tool");
  // NaN: the tool's default (stepover, step-down) or the strategy's (tolerance).
  if (!std::isnan(p.stepover)) check_range(p.stepover, 0, 500, "parameter stepover", "mm", Bound::Open);
  if (!std::isnan(p.stepdown)) check_range(p.stepdown, 0, 500, "parameter stepdown", "mm", Bound::Open);
  // A tolerance below a nanometre is below what a double resolves on a part of a metre: the searches that
  // refine to it would not end.
  if (!std::isnan(p.tolerance)) check_range(p.tolerance, 1e-6, 10, "parameter tolerance", "mm");
  check_range(p.allowance, 0, 50, "parameter allowance", "mm");
  check_range(p.angle_deg, -360, 360, "parameter angle", "degrees");
  check_range(p.stock_margin, 0, 1000, "parameter stock_margin", "mm");
  check_range(p.safe_clearance, 0, 1000, "parameter safe_clearance", "mm", Bound::Open);
  check_range(p.link_clearance, 0, 1000, "parameter link_clearance", "mm", Bound::Open);
  check_range(p.approach, 0, 1000, "parameter approach", "mm");
  if (!std::isnan(p.air_gap)) check_range(p.air_gap, 0, 1000, "parameter air_gap", "mm");
  // Radial engagement of adaptive clearing: above 0 (no cut at all) and at most a full-width slot.
  if (!std::isnan(p.engagement_deg)) check_range(p.engagement_deg, 0, 180, "parameter engagement", "degrees", Bound::Open);
  check_range(p.max_feed, 0, 1e6, "parameter max_feed", "mm/min");
  const ToolAxisParams& a = p.tool_axis;
  if (!std::isnan(a.lead_deg)) check_range(a.lead_deg, -45, 45, "parameter lead", "degrees");
  check_range(a.tilt_deg, -45, 45, "parameter tilt", "degrees");
  check_range(a.cone_deg, 0, 90, "parameter cone", "degrees");
  check_range(a.rate_deg_per_mm, 0, 180, "parameter axis_rate", "degrees per mm", Bound::Open);
  if (p.material) p.material->check("parameter material");
}

}  // namespace rosmill::core
