// Every name `rosmill plan --strategy` takes: the strategies of the table (planned on the mesh) and the presets
// and templates of config/presets.yaml (planned on the cloud of the mesh's vertices, the input they were written
// for), for the tests that run every one of them.
#pragma once
#include <string>
#include <vector>

#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/planner/strategy_table.hpp"

namespace rosmill::core::test {

inline const PresetTable& package_presets() {
  static const PresetTable table = read_presets(ROSMILL_SOURCE_DIR "/config/presets.yaml");
  return table;
}

struct PlanName {
  std::string name;
  bool on_cloud = false;  // a preset or template: on the cloud
  bool is_template = false;
  bool multi_axis = false;  // posted for a trunnion with tool-centre-point control (multi_axis_post below)
};

inline std::vector<PlanName> plan_names() {
  std::vector<PlanName> names;
  for (const StrategyEntry& s : strategies()) names.push_back({s.name, false, false, s.multi_axis});
  for (const Preset& p : package_presets().presets) names.push_back({p.name, true, false});
  for (const PlanTemplate& t : package_presets().templates) names.push_back({t.name, true, true});
  return names;
}

// Plans `n` with `params` (a template with its presets' tools).
inline Job plan_named(const PlanName& n, const Mesh& mesh, const PointCloud& cloud, const PlanParams& params) {
  PlanningRequest r;
  if (n.on_cloud) r.input.cloud = &cloud;
  else r.input.mesh = &mesh;
  r.strategy = n.name;
  r.params = params;
  if (n.is_template) r.params.tool = Tool{};
  r.presets = &package_presets();
  return plan(r);
}

// The post's options for a multi-axis strategy's program: LinuxCNC's trunnion simulator with tool-centre-point
// control (config/machine_xyzac_tcp.yaml), whose limits it is checked against.
inline const gcode::MachineLimits& tool_centre_point_machine() {
  static const gcode::MachineLimits m = gcode::load_machine_limits(ROSMILL_SOURCE_DIR "/config/machine_xyzac_tcp.yaml");
  return m;
}
inline gcode::PostOptions multi_axis_post(gcode::PostOptions o) {
  return gcode::with_tool_centre_point(std::move(o), tool_centre_point_machine(), "test");
}

}  // namespace rosmill::core::test
