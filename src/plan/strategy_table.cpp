#include <sstream>

#include "rosmill/error.hpp"
#include "rosmill/plan/strategy.hpp"
#include "rosmill/slice/contour_toolpath.hpp"

namespace rosmill {

// Every strategy, one line each. A strategy's own header declares its function.
const std::vector<StrategyEntry>& strategies() {
  static const std::vector<StrategyEntry> table = {
      {"contour", "Z-level contours of the slices offset by a flat end mill's radius", true, false, plan_contour},
  };
  return table;
}

Job plan(const std::string& name, const PlanInput& input, const PlanParams& params,
              const PlanProgress& progress) {
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
