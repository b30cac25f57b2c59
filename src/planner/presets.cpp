#include "rosmill/planner/presets.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/input_file.hpp"
#include "rosmill/yaml/fields.hpp"

namespace rosmill::core {
namespace {

Preset read_preset(const YAML::Node& node, const ToolTable& tools, const std::string& file, size_t index) {
  const yaml::Fields f(
      node, file, "presets[" + std::to_string(index) + "]",
      {"name", "strategy", "description", "tool", "stepover", "stepdown", "allowance", "tolerance", "sampling"});
  Preset p;
  p.name = f.text("name", "", true);
  p.strategy = f.text("strategy", "", true);
  p.description = f.text("description", "");
  const double id = f.required_number("tool", 1, kMaxToolNumber);
  if (id != std::floor(id)) f.fail("tool", "must name a tool of the table by its id");
  try {
    p.tool = tools.get(int(id));
  } catch (const Error& e) {
    f.fail("tool", e.what());
  }
  p.stepover = f.number("stepover", NAN, 0);
  p.stepdown = f.number("stepdown", NAN, 0);
  p.allowance = f.number("allowance", 0.0, 0);
  p.tolerance = f.number("tolerance", NAN, 0);
  const std::string sampling = f.text("sampling", "");
  if (!sampling.empty()) p.sampling = parse_sampling(sampling, f.where("sampling"));
  return p;
}

PlanTemplate read_template(const YAML::Node& node, const PresetTable& table, const std::string& file, size_t index) {
  const yaml::Fields f(node, file, "templates[" + std::to_string(index) + "]",
                       {"name", "description", "stages", "weights"});
  PlanTemplate t;
  t.name = f.text("name", "", true);
  t.description = f.text("description", "");
  const YAML::Node stages = f.node("stages");
  if (!stages || !stages.IsSequence() || stages.size() == 0) f.fail("stages", "must list presets by name");
  for (const YAML::Node& s : stages) {
    if (!s.IsScalar()) throw Error(f.where_at(s, "stages"), "must list presets by name");
    t.stages.push_back(s.Scalar());
    if (!table.find(t.stages.back()))
      throw Error(f.where_at(s, "stages"), "'" + t.stages.back() + "' is not a preset of the table");
  }
  const YAML::Node weights = f.node("weights");
  if (!weights) {
    t.weights.assign(t.stages.size(), 1.0 / double(t.stages.size()));
    return t;
  }
  if (!weights.IsSequence()) f.fail("weights", "must list one share per stage");
  double sum = 0;
  for (const YAML::Node& w : weights) {
    const double share = f.converted<double>(w, "weights", "expected a number");
    if (!std::isfinite(share) || share < 0) throw Error(f.where_at(w, "weights"), "must hold numbers >= 0");
    t.weights.push_back(share);
    sum += share;
  }
  if (t.weights.size() != t.stages.size() || !(std::abs(sum - 1.0) < 1e-6))
    f.fail("weights", "must give one share per stage, summing to 1");
  return t;
}

}  // namespace

const Preset* PresetTable::find(const std::string& name) const {
  for (const Preset& p : presets)
    if (p.name == name) return &p;
  return nullptr;
}

const PlanTemplate* PresetTable::find_template(const std::string& name) const {
  for (const PlanTemplate& t : templates)
    if (t.name == name) return &t;
  return nullptr;
}

PresetTable parse_presets(const std::string& yaml_text, const std::string& name) {
  // The presets' tools are a tool table in the same file (config/tools.yaml's format).
  const ToolTable tools = parse_tool_table(yaml_text, name, {"presets", "templates"});
  const yaml::Fields f(yaml::parse(yaml_text, name), name, "", {"tools", "presets", "templates"});
  PresetTable table;
  table.source = name;
  const YAML::Node presets = f.node("presets");
  if (!presets || !presets.IsSequence()) f.fail("presets", "expected a list of presets");
  for (size_t i = 0; i < presets.size(); ++i) table.presets.push_back(read_preset(presets[i], tools, name, i));
  const YAML::Node templates = f.node("templates");
  if (templates && !templates.IsSequence()) f.fail("templates", "expected a list of templates");
  for (size_t i = 0; templates && i < templates.size(); ++i)
    table.templates.push_back(read_template(templates[i], table, name, i));
  return table;
}

PresetTable read_presets(const std::string& path) {
  return parse_presets(read_input_file(path), path);
}

bool tool_unset(const Tool& t) {
  const Cutter d;
  return t.name.empty() && t.cutter.type == d.type && t.cutter.diameter == d.diameter &&
         t.cutter.corner_radius == d.corner_radius;
}

PlanParams preset_params(const Preset& preset, const PlanParams& given) {
  PlanParams p = given;
  if (tool_unset(given.tool)) {
    // The preset's stepover and step-down belong to its tool: a tool of the caller's brings its own.
    p.tool = preset.tool;
    if (std::isnan(p.stepover)) p.stepover = preset.stepover;
    if (std::isnan(p.stepdown)) p.stepdown = preset.stepdown;
  }
  if (std::isnan(p.tolerance)) p.tolerance = std::isnan(preset.tolerance) ? 0.001 : preset.tolerance;
  p.allowance = given.allowance + preset.allowance;
  p.sampling = preset.sampling;
  return p;
}

}  // namespace rosmill::core
