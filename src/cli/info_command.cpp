#include "info_command.hpp"

#include <cstdio>
#include <iostream>

#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"

namespace rosmill::core::cli {

nlohmann::json box_json(const Box3& box) {
  return {{"min", {box.min.x(), box.min.y(), box.min.z()}}, {"max", {box.max.x(), box.max.y(), box.max.z()}}};
}

namespace {

nlohmann::json mesh_info(const std::string& file, const std::string& units) {
  StlReadOptions options;
  if (!units.empty()) options.units = parse_units(units, "--units");
  StlInfo info;
  // The report straight from the welded triangles: the same figures as a Mesh's, without its derived tables.
  const MeshReport r = report(read_stl_triangles(file, options, &info));
  nlohmann::json j = {{"kind", "mesh"},
                      {"format", info.ascii ? "ascii" : "binary"},
                      {"triangles", r.triangles},
                      {"vertices", r.vertices},
                      {"bbox", box_json(r.bbox)},
                      {"closed", r.closed},
                      {"open_edges", r.open_edges},
                      {"nonmanifold_edges", r.nonmanifold_edges},
                      {"inconsistent_edges", r.inconsistent_edges},
                      {"degenerate", r.degenerate},
                      {"area", r.area},
                      {"stored_normal_mismatches", info.stored_normal_mismatches}};
  if (r.closed) j["volume"] = r.volume;  // a signed-volume sum means nothing for an open surface
  if (info.ascii) j["solids"] = info.solids;
  return j;
}

std::string triple(const nlohmann::json& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%.6g %.6g %.6g", v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  return buf;
}

// The same facts as the JSON, one per line, for a person.
void print_text(const std::string& file, const nlohmann::json& j) {
  std::printf("%s: %s (%s)\n", file.c_str(), j["kind"].get<std::string>().c_str(),
              j["format"].get<std::string>().c_str());
  const auto& box = j["bbox"];
  for (const char* key : {"triangles", "vertices", "points", "points_in_file", "dropped_nonfinite", "solids"})
    if (j.contains(key)) std::printf("  %-26s %zu\n", key, j[key].get<size_t>());
  std::printf("  %-26s %s\n", "bbox min (mm)", triple(box["min"]).c_str());
  std::printf("  %-26s %s\n", "bbox max (mm)", triple(box["max"]).c_str());
  if (j["kind"] != "mesh") return;
  std::printf("  %-26s %.6g\n", "area (mm^2)", j["area"].get<double>());
  std::printf("  %-26s %s\n", "closed", j["closed"].get<bool>() ? "yes" : "no");
  if (j.contains("volume")) std::printf("  %-26s %.6g\n", "volume (mm^3)", j["volume"].get<double>());
  for (const char* key : {"open_edges", "nonmanifold_edges", "inconsistent_edges", "degenerate",
                          "stored_normal_mismatches"})
    std::printf("  %-26s %zu\n", key, j[key].get<size_t>());
}

}  // namespace

void add_info_command(CLI::App& app, CloudInfoReader cloud_info) {
  auto* cmd = app.add_subcommand("info", "print the report of a mesh (STL) or a point cloud (PCD, PLY)");
  auto file = std::make_shared<std::string>();
  auto units = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("FILE", *file, "STL (also .stl.gz), PCD or PLY file")->required();
  cmd->add_option("--units", *units, "units of the file's numbers: mm, inch or m (default mm for STL, m for clouds)")
      ->check(CLI::IsMember({"mm", "inch", "in", "m"}));
  cmd->add_flag("--json", *json, "print one JSON object");
  cmd->callback([file, units, json, cloud_info] {
    const nlohmann::json j = is_cloud_file(*file) ? cloud_info(*file, *units) : mesh_info(*file, *units);
    if (*json)
      std::cout << j.dump() << std::endl;
    else
      print_text(*file, j);
  });
}

}  // namespace rosmill::core::cli
