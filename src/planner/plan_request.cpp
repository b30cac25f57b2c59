#include "rosmill/planner/plan_request.hpp"

#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include "rosmill/cloud/cloud_surface.hpp"
#include "rosmill/error.hpp"
#include "rosmill/plan/kept_moves.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/plan/tool_body_surface.hpp"
#include "rosmill/planner/strategy_table.hpp"

namespace rosmill::core {
namespace {

std::string known_names(const PresetTable* presets) {
  std::ostringstream known;
  for (const StrategyEntry& s : strategies()) known << (known.tellp() > 0 ? ", " : "") << s.name;
  if (presets) {
    for (const Preset& p : presets->presets) known << ", " << p.name;
    for (const PlanTemplate& t : presets->templates) known << ", " << t.name;
  }
  return known.str();
}

// The input's Surface, built once for the request (and only when a strategy asks for it).
class InputSurface {
 public:
  InputSurface(const PlanInput& input, double tolerance) : input_(input), tolerance_(tolerance) {}
  const Surface& get() {
    if (input_.surface) return *input_.surface;
    if (!owned_) owned_ = build();
    return *owned_;
  }

 private:
  std::unique_ptr<Surface> build() const {
    if (input_.mesh) return std::make_unique<MeshSurface>(*input_.mesh);
    if (input_.cloud->points.empty()) throw Error("plan", "the point cloud is empty");
    CloudSurfaceOptions o;
    o.max_sink = std::isnan(input_.max_sink) ? tolerance_ : input_.max_sink;
    o.holes = input_.holes;
    return std::make_unique<CloudSurface>(*input_.cloud, o);
  }
  const PlanInput& input_;
  double tolerance_;
  std::unique_ptr<Surface> owned_;
};

// Runs one strategy; `name` (the strategy's, or the preset's that chose it) names its toolpaths and report.
Job run(const StrategyEntry& entry, const std::string& name, const PlanningRequest& r, InputSurface& surface,
        const PlanParams& params, const PlanProgress& progress) {
  if (entry.needs_mesh && !r.input.mesh)
    throw Error("strategy " + name,
                "needs a mesh (an STL file), got a " + std::string(r.input.cloud ? "cloud" : "surface"));
  check_plan_params(params);
  PlanReport report;
  // Every strategy keeps the tool's shank and holder out of the part as it keeps the cutter out; a finishing one out
  // of the material a job's stock still holds too. Roughing removes that material level by level as it goes down,
  // so the stock before it is no bound: the job sweeps its bodies through the stock as it cuts (body_collision.hpp).
  std::optional<ToolBodySurface> body;
  if (!entry.needs_mesh)
    body.emplace(surface.get(), params.tool, entry.roughing ? nullptr : params.material, params.allowance);
  const Surface* planned_on = !body ? nullptr : body->body_matters() ? &*body : &surface.get();
  const StrategyCall call{planned_on, r.input.mesh, params, progress, &report};
  Job job = entry.function(call);
  // Rest machining: whatever the strategy, only where an earlier tool left rest material.
  if (params.material && params.material->keeps() && !entry.follows_material) {
    KeepOptions rest;
    rest.link_clearance = params.link_clearance;
    rest.approach = params.approach;
    job = keep_to_cells(job, *params.material, rest);
  }
  for (Toolpath& tp : job) {
    tp.strategy = name;
    tp.tolerance = std::isnan(params.tolerance) ? kDefaultTolerance : params.tolerance;
  }
  if (r.reports) {
    report.strategy = name;
    report.cl_points = 0;
    for (const Toolpath& tp : job) report.cl_points += tp.move_count();
    r.reports->push_back(report);
  }
  return job;
}

const StrategyEntry& entry_of(const Preset& p, const PresetTable& table) {
  const StrategyEntry* e = find_strategy(p.strategy);
  if (!e) throw Error(table.source + ": preset " + p.name, "unknown strategy '" + p.strategy + "'");
  return *e;
}

// The tolerance the input's surface is built with: the given one, else the (first) preset's, else the engine's.
double surface_tolerance(const PlanningRequest& r, const Preset* preset) {
  if (!std::isnan(r.params.tolerance)) return r.params.tolerance;
  return preset ? preset_params(*preset, r.params).tolerance : kDefaultTolerance;
}

}  // namespace

void check_plan_name(const std::string& name, const PresetTable* presets, const std::string& where) {
  if (find_strategy(name) || (presets && (presets->find(name) || presets->find_template(name)))) return;
  throw Error(where, "unknown strategy '" + name + "' (known: " + known_names(presets) + ")");
}

PlanKind plan_kind(const std::string& name, const PresetTable* presets, const std::string& where) {
  check_plan_name(name, presets, where);
  std::vector<std::string> strategies;
  if (find_strategy(name)) {
    strategies.push_back(name);
  } else if (const Preset* p = presets->find(name)) {
    strategies.push_back(p->strategy);
  } else {
    for (const std::string& stage : presets->find_template(name)->stages)
      strategies.push_back(presets->find(stage)->strategy);
  }
  PlanKind k;
  for (const std::string& s : strategies) {
    const StrategyEntry* e = find_strategy(s);
    if (!e) throw Error(where, "unknown strategy '" + s + "'");
    k.needs_mesh |= e->needs_mesh;
    k.roughing &= e->roughing;
    k.follows_material &= e->follows_material;
    k.multi_axis |= e->multi_axis;
  }
  return k;
}

namespace {

// The request on copies of the part (and stock) turned for the setup.
Job plan_turned(const PlanningRequest& r) {
  if (r.input.surface)
    throw Error("setup " + r.input.setup.name, "a surface the caller built is planned as it is: turn it first");
  PlanningRequest turned = r;
  turned.input.setup = SetupFrame{};
  Mesh mesh, stock;
  PointCloud cloud;
  const Placement& into = r.input.setup.placement;
  if (r.input.mesh) turned.input.mesh = &(mesh = placed(*r.input.mesh, into));
  if (r.input.cloud) turned.input.cloud = &(cloud = placed(*r.input.cloud, into));
  if (r.params.stock_mesh) turned.params.stock_mesh = &(stock = placed(*r.params.stock_mesh, into));
  return plan(turned);
}

}  // namespace

Job plan(const PlanningRequest& r) {
  check_setup(r.input.setup);
  if (!r.input.setup.identity()) return plan_turned(r);
  const int given = (r.input.mesh != nullptr) + (r.input.cloud != nullptr) + (r.input.surface != nullptr);
  if (given != 1) throw Error("strategy " + r.strategy, given ? "give one input, not several" : "nothing to plan on");
  check_plan_name(r.strategy, r.presets, "strategy");
  if (r.input.mesh) check_has_area(*r.input.mesh, "plan: the part");
  if (r.params.stock_mesh) check_has_area(*r.params.stock_mesh, "plan: the stock");
  if (!std::isnan(r.params.tolerance) && !(r.params.tolerance > 0 && std::isfinite(r.params.tolerance)))
    throw Error("parameter tolerance", "must be a positive number");
  const PlanTemplate* tmpl = r.presets ? r.presets->find_template(r.strategy) : nullptr;
  const Preset* preset = r.presets ? r.presets->find(tmpl ? tmpl->stages.front() : r.strategy) : nullptr;
  InputSurface surface(r.input, surface_tolerance(r, preset));
  if (!tmpl && !preset) {
    const StrategyEntry& e = *find_strategy(r.strategy);
    return run(e, e.name, r, surface, r.params, r.progress);
  }
  if (!tmpl)
    return run(entry_of(*preset, *r.presets), preset->name, r, surface, preset_params(*preset, r.params), r.progress);
  // A template: its stages in order, each with its preset's tool, progress weighted by the stages' shares.
  if (!tool_unset(r.params.tool))
    throw Error("template " + tmpl->name, "runs its presets' tools; give a tool to one of its stages instead");
  Job job;
  double from = 0.0;
  for (size_t k = 0; k < tmpl->stages.size(); ++k) {
    const Preset& stage = *r.presets->find(tmpl->stages[k]);
    const double to = k + 1 == tmpl->stages.size() ? 1.0 : from + tmpl->weights[k];
    const PlanProgress part = [&r, from, to](double f) { return !r.progress || r.progress(from + (to - from) * f); };
    for (Toolpath& tp : run(entry_of(stage, *r.presets), stage.name, r, surface, preset_params(stage, r.params), part))
      job.push_back(std::move(tp));
    from = to;
  }
  return job;
}

}  // namespace rosmill::core
