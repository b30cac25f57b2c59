// rosmill info FILE [--units mm|inch|m] [--json]: the mesh report of an STL, or the summary of a point cloud.
// Everything printed is in millimetres; --units says what the file's numbers are (default: mm for STL, m for
// clouds, as CAD and ROS customs have it). This is rosmill-full's; the `rosmill` front adds the same command
// without the cloud reader.
#include "command.hpp"
#include "info_command.hpp"
#include "rosmill/io/cloud_io.hpp"

namespace rosmill::core::cli {
namespace {

nlohmann::json cloud_info(const std::string& file, const std::string& units) {
  CloudReadOptions options;
  if (!units.empty()) options.units = parse_units(units, "--units");
  CloudInfo info;
  const PointCloud cloud = read_cloud(file, options, &info);
  return {{"kind", "cloud"},
          {"format", info.format},
          {"points", cloud.points.size()},
          {"points_in_file", info.points_in_file},
          {"dropped_nonfinite", info.dropped_nonfinite},
          {"bbox", box_json(cloud.bbox)}};
}

CommandRegistration reg([](CLI::App& app) { add_info_command(app, cloud_info); });

}  // namespace
}  // namespace rosmill::core::cli
