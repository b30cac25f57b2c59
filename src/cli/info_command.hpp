// The `info` command, shared by the `rosmill` front (which reads meshes itself and hands clouds to rosmill-full,
// so that it links neither PCL nor VTK) and rosmill-full (which reads both).
#pragma once
#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::cli {

// The summary of a point cloud file as JSON; `units` as given to --units (empty: the default).
using CloudInfoReader = std::function<nlohmann::json(const std::string& file, const std::string& units)>;

nlohmann::json box_json(const Box3& box);

// Adds `info FILE [--units mm|inch|m] [--json]`: the mesh report of an STL, or what `cloud_info` says of a cloud.
void add_info_command(CLI::App& app, CloudInfoReader cloud_info);

}  // namespace rosmill::core::cli
