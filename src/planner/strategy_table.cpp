#include "rosmill/planner/strategy_table.hpp"

#include "rosmill/plan/adaptive.hpp"
#include "rosmill/plan/contour_toolpath.hpp"
#include "rosmill/plan/five_axis_finish.hpp"
#include "rosmill/plan/four_axis_finish.hpp"
#include "rosmill/plan/grid_rough.hpp"
#include "rosmill/plan/raster.hpp"
#include "rosmill/plan/rough.hpp"
#include "rosmill/plan/stock.hpp"
#include "rosmill/plan/waterline.hpp"

namespace rosmill::core {
namespace {

Job raster_entry(const StrategyCall& c) {
  RasterOptions o;
  o.report = c.report;
  return raster_on(*c.surface, c.params, o, c.progress);
}

// A stock mesh must be closed and, for a mesh input, hold the part.
Job rough_entry(const StrategyCall& c) {
  if (c.params.stock_mesh) check_stock_mesh(*c.params.stock_mesh, c.mesh);
  return rough_strategy(*c.surface, c.params, c.progress);
}

Job adaptive_entry(const StrategyCall& c) {
  if (c.params.stock_mesh) check_stock_mesh(*c.params.stock_mesh, c.mesh);
  return adaptive_strategy(*c.surface, c.params, c.progress, c.report);
}

}  // namespace

// Every strategy, one line each. A strategy's own header declares its function.
const std::vector<StrategyEntry>& strategies() {
  static const std::vector<StrategyEntry> table = {
      {"raster", "parallel zigzag finishing at a stepover and angle (sampling: chord or step-error)", false,
       raster_entry},
      {"waterline", "closed z-level finishing loops every step-down", false,
       [](const StrategyCall& c) { return waterline_strategy(*c.surface, c.params, c.progress); }},
      {"rough", "z-level zigzag area clearing with ramp entry", false, rough_entry, true},
      {"adaptive", "z-level clearing at a bounded radial engagement (--engagement), helix or ramp entry", false,
       adaptive_entry, true, true},
      {"grid-rough", "grid-method roughing (Muslimin et al.): levels of the step-down, staircase over the drops", false,
       [](const StrategyCall& c) { return grid_rough_on(*c.surface, c.params, c.progress, c.report); }, true},
      {"contour", "Z-level contours of the slices offset by a flat end mill's radius", true,
       [](const StrategyCall& c) { return plan_contour(*c.mesh, c.params, c.progress); }},
      {"five-axis", "ball-end raster finishing with a tool axis at every cutter location (lead, tilt, cone, rate)",
       true, [](const StrategyCall& c) { return five_axis_finish(*c.mesh, c.params, c.progress, c.report); }, false,
       false, true},
      {"four-axis", "ball-end rings round the part's Z axis, the tool axis across it: a rotary axis follows the angle",
       true, [](const StrategyCall& c) { return four_axis_finish(*c.mesh, c.params, c.progress, c.report); }, false,
       false, true},
  };
  return table;
}

const StrategyEntry* find_strategy(const std::string& name) {
  for (const StrategyEntry& s : strategies())
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace rosmill::core
