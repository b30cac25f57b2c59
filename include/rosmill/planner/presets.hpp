// Named planning presets (config/presets.yaml): a strategy with its tool, stepover, step-down, allowance,
// tolerance and sampling policy, on a mesh or a cloud alike; and templates, presets run in order as one job
// (the rough, semi-finish and finish stages of Muslimin et al., "Direct NC Toolpath Generation from 3D Point
// Cloud Datasets", are the presets cloud-rough, cloud-semi, cloud-finish and the template cloud-all).
//
// presets.yaml:  tools: [ ... ]                      the presets' own tools, as in config/tools.yaml
//                presets: [{name, strategy, tool: ID, stepover, stepdown, allowance, tolerance, sampling,
//                           description}, ...]        stepover, stepdown, tolerance optional (the tool's / 0.001)
//                templates: [{name, stages: [preset, ...], weights: [share of the progress, ...], description}]
#pragma once
#include <string>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/plan/plan_params.hpp"

namespace rosmill::core {

struct Preset {
  std::string name, description, strategy;
  Tool tool;
  double stepover = NAN, stepdown = NAN;  // NaN: the tool's (or the strategy's own default)
  double allowance = 0.0;                 // left above the plan's own allowance (the final part's)
  double tolerance = NAN;                 // NaN: the engine's 0.001 mm
  Sampling sampling = Sampling::Chord;
};

struct PlanTemplate {
  std::string name, description;
  std::vector<std::string> stages;  // preset names, in machining order
  std::vector<double> weights;      // each stage's share of the progress (sum 1)
};

struct PresetTable {
  std::string source;
  std::vector<Preset> presets;
  std::vector<PlanTemplate> templates;
  const Preset* find(const std::string& name) const;
  const PlanTemplate* find_template(const std::string& name) const;
};

// Reads and validates a table; errors name the file, the entry and the field. A template's stages must be
// presets of the table; a preset's strategy is checked when it is planned.
PresetTable read_presets(const std::string& path);
PresetTable parse_presets(const std::string& yaml_text, const std::string& name);

// True for a default-constructed tool: the caller gave none, the preset's applies.
bool tool_unset(const Tool& tool);
// The parameters a preset plans with: the given ones, where the caller left the tool unset the preset's tool with
// its stepover and step-down (unless given), the preset's tolerance where the given one is NaN, the preset's
// allowance on top of the given one, and its sampling.
PlanParams preset_params(const Preset& preset, const PlanParams& given);

}  // namespace rosmill::core
