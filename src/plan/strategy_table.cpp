#include <sstream>

#include "rosmill/cloud/cloud_plan.hpp"
#include "rosmill/error.hpp"
#include "rosmill/plan/strategy.hpp"
#include "rosmill/plan/raster.hpp"
#include "rosmill/plan/rough.hpp"
#include "rosmill/plan/waterline.hpp"
#include "rosmill/slice/contour_toolpath.hpp"

namespace rosmill {

// Every strategy, one line each. A strategy's own header declares its function.
const std::vector<StrategyEntry>& strategies() {
  static const std::vector<StrategyEntry> table = {
      {"raster", "parallel zigzag finishing at a stepover and angle", false, false, on_surface(raster_strategy)},
      {"waterline", "closed z-level finishing loops every step-down", false, false, on_surface(waterline_strategy)},
      {"rough", "z-level zigzag area clearing with ramp entry", false, false, plan_rough},
      {"contour", "Z-level contours of the slices offset by a flat end mill's radius", true, false, plan_contour},
      {"cloud-rough", "seed 004 roughing of a point cloud: flat 10 mm, grid 2R-0.5δ, levels of d", false, true, cloud_rough_strategy},
      {"cloud-semi", "seed 004 semi-finishing of a point cloud: ball 5 mm raster, buffer points", false, true, cloud_semi_strategy},
      {"cloud-finish", "seed 004 finishing of a point cloud: ball 3 mm raster, buffer points", false, true, cloud_finish_strategy},
      {"cloud-all", "seed 004 rough + semi + finish of a point cloud (three toolpaths)", false, true, cloud_all_strategy},
  };
  return table;
}

Job plan(const std::string& name, const PlanInput& input, const PlanParams& params, const PlanProgress& progress) {
  for (const StrategyEntry& s : strategies()) {
    if (s.name != name) continue;
    if (s.needs_mesh && !input.mesh) throw Error("strategy " + name, "needs a mesh (an STL file), got a cloud");
    if (s.needs_cloud && !input.cloud) throw Error("strategy " + name, "needs a point cloud, got a mesh");
    if (!input.mesh && !input.cloud) throw Error("strategy " + name, "nothing to plan on");
    return s.function(input, params, progress);
  }
  std::ostringstream known;
  for (const StrategyEntry& s : strategies()) known << (known.tellp() > 0 ? ", " : "") << s.name;
  throw Error("strategy", "unknown strategy '" + name + "' (known: " + known.str() + ")");
}

}  // namespace rosmill
