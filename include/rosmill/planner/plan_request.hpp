// The one entry point of planning: plan(request). The request (PlanningRequest: the ROS service Plan already
// generates rosmill::core::PlanRequest) names what to plan on (a mesh, a prepared cloud with its hole policy, or a
// surface the caller built), a strategy, preset or template by name, the parameters and the progress callback.
// plan() builds the input's Surface (a mesh's triangles, a cloud's points) and runs the strategy on it; mesh and
// cloud differ only there and in the options that belong to the input.
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "rosmill/cloud/cloud_holes.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/plan/plan_params.hpp"
#include "rosmill/plan/plan_report.hpp"
#include "rosmill/plan/surface.hpp"
#include "rosmill/planner/presets.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/toolpath/job.hpp"

namespace rosmill::core {

// What to plan on (millimetres, machined side facing +Z, in the workpiece frame): exactly one of the three.
struct PlanInput {
  const Mesh* mesh = nullptr;
  const PointCloud* cloud = nullptr;      // prepared (cloud/cloud_input.hpp)
  const Surface* surface = nullptr;       // built by the caller, used as it is
  HolePolicy holes = HolePolicy::Bridge;  // cloud: over missing data, bridge on lids or skip
  double max_sink = NAN;                  // cloud: sink allowed between points (mm); NaN: the plan's tolerance
  // The setup: plan() turns the part (and a stock mesh) so that the setup's tool axis points up, and the toolpath
  // is in the turned part's frame. A surface the caller built is planned as it is (only +Z).
  SetupFrame setup;
};

struct PlanningRequest {
  PlanInput input;
  std::string strategy;  // a strategy of the table, a preset or a template of `presets`
  PlanParams params;     // for a preset: NaN tolerance and an unset tool take the preset's
  PlanProgress progress;
  const PresetTable* presets = nullptr;        // not owned; null: the strategies only
  std::vector<PlanReport>* reports = nullptr;  // when given: one report per toolpath planned
};

// Throws Error naming the strategy when it is unknown (listing the known names) or does not fit the input, and
// Error("plan", "cancelled") when the progress callback says stop.
Job plan(const PlanningRequest& request);

// Throws the error plan() would give for an unknown name.
void check_plan_name(const std::string& name, const PresetTable* presets, const std::string& where);

// What a strategy, preset or template plans: on the mesh itself rather than a Surface (any of its stages), and
// whether every stage clears stock in levels (roughing) rather than finishing the surface. Throws like
// check_plan_name.
struct PlanKind {
  bool needs_mesh = false, roughing = true;
  bool follows_material = true;  // every stage cuts only what the job's material grid holds (StrategyEntry)
  bool multi_axis = false;       // some stage gives a tool axis at every move
};
PlanKind plan_kind(const std::string& name, const PresetTable* presets, const std::string& where);

}  // namespace rosmill::core
