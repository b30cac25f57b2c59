// --work-offset: where the program's origin (G54) lies on the machine, set by the program itself (G10 L2 P1,
// gcode/work_offset.hpp). Either numbers, "x,y,z[,rotation_deg]" (mm, degrees), or the JSON that
// `rosmill register --json` printed for a scan taken in machine coordinates: the design's pose there is the
// workpiece's. An ambiguous registration is refused: the part could sit in another pose.
#pragma once
#include <CLI/CLI.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/gcode/work_offset.hpp"
#include "rosmill/input_file.hpp"

namespace rosmill::core::cli {

struct WorkOffsetArgs {
  std::string given;          // numbers or a registration JSON file; empty: the controller's G54 as it stands
  double max_tilt_deg = 0.05;
};

inline void add_work_offset_option(CLI::App* cmd, WorkOffsetArgs& a) {
  cmd->add_option("--work-offset", a.given,
                  "set G54 in the program (G10 L2 P1): x,y,z[,rotation_deg] in mm, or the JSON of rosmill register "
                  "--json for a scan in machine coordinates");
  cmd->add_option("--max-tilt", a.max_tilt_deg, "degrees: refuse a registered part tilted more than this (0.05)");
}

// The pose in `rosmill register --json` output, checked; Error naming the file.
inline Eigen::Matrix4d registered_pose(const std::string& path) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_input_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw Error(path, std::string("not JSON: ") + e.what());
  }
  const nlohmann::json* t = j.is_object() && j.contains("transform") ? &j["transform"] : nullptr;
  if (!t || !t->is_array() || t->size() != 4)
    throw Error(path, "no \"transform\" (4 rows of 4 numbers, as rosmill register --json prints)");
  if (j.value("ambiguous", false))
    throw Error(path, "the registration is ambiguous (" + j.value("ambiguity", std::string("")) +
                          "): the part could sit in another pose; resolve it before machining");
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    const nlohmann::json& row = (*t)[r];
    if (!row.is_array() || row.size() != 4) throw Error(path, "\"transform\" row " + std::to_string(r + 1) +
                                                                  " is not 4 numbers");
    for (int c = 0; c < 4; ++c) {
      if (!row[c].is_number()) throw Error(path, "\"transform\" has a value that is not a number");
      m(r, c) = row[c].get<double>();
    }
  }
  return m;
}

inline std::optional<gcode::WorkOffset> work_offset_of(const WorkOffsetArgs& a) {
  if (a.given.empty()) return std::nullopt;
  if (std::filesystem::is_regular_file(a.given))
    return gcode::work_offset_of_pose(registered_pose(a.given), a.max_tilt_deg, "--work-offset " + a.given);
  return gcode::parse_work_offset(a.given, "--work-offset");
}

}  // namespace rosmill::core::cli
