#include "rosmill/planner/presets.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/input_file.hpp"

namespace rosmill::core {
namespace {

double optional_number(const YAML::Node& node, const char* field, double fallback, const std::string& where) {
  const YAML::Node v = node[field];
  if (!v) return fallback;
  double x = 0;
  try {
    x = v.as<double>();
  } catch (const YAML::Exception&) {
    throw Error(where, std::string("field '") + field + "' is not a number");
  }
  if (!std::isfinite(x) || x < 0) throw Error(where, std::string("field '") + field + "' must be a number >= 0");
  return x;
}

std::string text(const YAML::Node& node, const char* field, bool required, const std::string& where) {
  const YAML::Node v = node[field];
  if (!v) {
    if (required) throw Error(where, std::string("field '") + field + "' is missing");
    return "";
  }
  if (!v.IsScalar()) throw Error(where, std::string("field '") + field + "' must be a text");
  return v.Scalar();
}

Preset read_preset(const YAML::Node& node, const ToolTable& tools, const std::string& where) {
  if (!node.IsMap()) throw Error(where, "must be a map of fields");
  Preset p;
  p.name = text(node, "name", true, where);
  const std::string at = where + " (" + p.name + ")";
  p.strategy = text(node, "strategy", true, at);
  p.description = text(node, "description", false, at);
  const double id = optional_number(node, "tool", 0, at);
  if (id < 1) throw Error(at, "field 'tool' must name a tool of the table by its id");
  p.tool = tools.get(int(id));
  p.stepover = optional_number(node, "stepover", NAN, at);
  p.stepdown = optional_number(node, "stepdown", NAN, at);
  p.allowance = optional_number(node, "allowance", 0.0, at);
  p.tolerance = optional_number(node, "tolerance", NAN, at);
  const std::string sampling = text(node, "sampling", false, at);
  if (!sampling.empty()) p.sampling = parse_sampling(sampling, at + ": field 'sampling'");
  return p;
}

PlanTemplate read_template(const YAML::Node& node, const PresetTable& table, const std::string& where) {
  if (!node.IsMap()) throw Error(where, "must be a map of fields");
  PlanTemplate t;
  t.name = text(node, "name", true, where);
  const std::string at = where + " (" + t.name + ")";
  t.description = text(node, "description", false, at);
  if (!node["stages"] || !node["stages"].IsSequence() || node["stages"].size() == 0)
    throw Error(at, "field 'stages' must list presets");
  for (const YAML::Node& s : node["stages"]) {
    if (!s.IsScalar()) throw Error(at, "field 'stages' must list presets by name");
    t.stages.push_back(s.Scalar());
    if (!table.find(t.stages.back())) throw Error(at, "stage '" + t.stages.back() + "' is not a preset of the table");
  }
  double sum = 0;
  if (node["weights"]) {
    if (!node["weights"].IsSequence()) throw Error(at, "field 'weights' must list one share per stage");
    for (const YAML::Node& w : node["weights"]) {
      double share = NAN;
      try {
        share = w.as<double>();
      } catch (const YAML::Exception&) {
      }
      if (!std::isfinite(share) || share < 0) throw Error(at, "field 'weights' must hold numbers >= 0");
      t.weights.push_back(share);
      sum += share;
    }
    if (t.weights.size() != t.stages.size() || !(std::abs(sum - 1.0) < 1e-6))
      throw Error(at, "field 'weights' must give one share per stage, summing to 1");
  } else {
    t.weights.assign(t.stages.size(), 1.0 / double(t.stages.size()));
  }
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
  const ToolTable tools = parse_tool_table(yaml_text, name);
  const YAML::Node root = YAML::Load(yaml_text);  // valid YAML: the tool table's reader has checked it
  PresetTable table;
  table.source = name;
  const YAML::Node presets = root["presets"];
  if (!presets || !presets.IsSequence()) throw Error(name, "has no 'presets' list");
  for (size_t i = 0; i < presets.size(); ++i)
    table.presets.push_back(read_preset(presets[i], tools, name + ": preset #" + std::to_string(i + 1)));
  const YAML::Node templates = root["templates"];
  if (templates && templates.IsSequence())
    for (size_t i = 0; i < templates.size(); ++i)
      table.templates.push_back(read_template(templates[i], table, name + ": template #" + std::to_string(i + 1)));
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
