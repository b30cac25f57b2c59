// Planning strategies by name, one line each in src/planner/strategy_table.cpp; each strategy lives in its own
// file (plan/, slice/) and is written once against a Surface, which plan(request) builds for the input. This is
// the top of planning: it may include cloud, slice and plan; none of them includes it.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/plan/plan_params.hpp"
#include "rosmill/plan/plan_report.hpp"
#include "rosmill/plan/surface.hpp"
#include "rosmill/toolpath/job.hpp"

namespace rosmill::core {

// What a strategy is run with: the input's surface (null for a strategy that works on the mesh itself), the mesh
// when the input is one, the resolved parameters, progress, and where to put its report (may be null).
struct StrategyCall {
  const Surface* surface = nullptr;
  const Mesh* mesh = nullptr;
  const PlanParams& params;
  const PlanProgress& progress;
  PlanReport* report = nullptr;
};

struct StrategyEntry {
  std::string name;
  std::string description;
  bool needs_mesh = false;  // works on the mesh itself (slices), not through a Surface
  std::function<Job(const StrategyCall&)> function;
  bool roughing = false;    // clears stock in levels down to the allowance, rather than following the surface
  // Cuts only the material a job's stock has left, by itself (its moves are not kept to rest cells afterwards).
  bool follows_material = false;
  // A tool axis at every cutter location (simultaneous four- or five-axis): posted for a machine with
  // tool-centre-point control only.
  bool multi_axis = false;
};

const std::vector<StrategyEntry>& strategies();
// The entry named `name`, or null.
const StrategyEntry* find_strategy(const std::string& name);

}  // namespace rosmill::core
