// Where a command finds a configuration file it was not given (config/tools.yaml, config/machine.yaml): the
// working folder's config/NAME when there is one (a cell keeps its own tools and machine next to its parts), else
// the package's own config folder (the source tree's in a build, share/rosmill/config once installed), so that
// the commands run from any folder.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/prepare_program.hpp"

namespace rosmill::core::cli {

inline std::string default_config(const std::string& name) {
  const std::string local = "config/" + name;
  if (std::filesystem::exists(local)) return local;
  const std::string source = std::string(ROSMILL_PACKAGE_CONFIG) + "/" + name;
  if (std::filesystem::exists(source)) return source;
  return std::string(ROSMILL_INSTALLED_CONFIG) + "/" + name;
}

// The machine file every written or sent program is checked against: `given` (--machine), else
// config/machine.yaml found as above. Throws Error when there is no such file.
inline std::string machine_file(const std::string& given) {
  const std::string path = given.empty() ? default_config("machine.yaml") : given;
  if (!std::filesystem::exists(path))
    throw Error("--machine", "no machine file '" + path + "': give --machine FILE (or --no-limits to go on "
                                                          "without checking the machine's limits)");
  return path;
}

// The machine's limits, or none with --no-limits (the only way to leave them unchecked).
inline std::optional<gcode::MachineLimits> machine_to_check(const std::string& given, bool no_limits) {
  if (no_limits) return std::nullopt;
  return gcode::load_machine_limits(machine_file(given));
}

// The trajectory planner that times programs: the machine file's (--machine, else config/machine.yaml as above,
// also with --no-limits); without any machine file, none (the time at the feeds alone).
inline gcode::TrajectoryLimits machine_trajectory(const std::string& given) {
  if (given.empty() && !std::filesystem::exists(default_config("machine.yaml"))) return {};
  return gcode::load_machine_limits(machine_file(given)).trajectory;
}

// A multi-axis job (a tool axis per move) is written for the machine file's trunnion with tool-centre-point control:
// its chain and safe Z go to the post, whether or not the limits are checked.
inline void post_for_machine(const Job& job, const std::string& machine, gcode::PostOptions& o) {
  bool multi_axis = false;
  for (const Toolpath& tp : job) multi_axis |= tp.multi_axis();
  if (!multi_axis) return;
  const std::string path = machine_file(machine);
  o = gcode::with_tool_centre_point(o, gcode::load_machine_limits(path), "--machine " + path);
}

}  // namespace rosmill::core::cli
