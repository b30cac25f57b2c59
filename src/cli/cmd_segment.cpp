// rosmill segment FILE [--threshold 0.4] [--min-facets N | --min-area-fraction F] [--setup LIST] [--units U]
//                      [--json]
// Phase 1 surface patches of an STL part, then for each setup (default: the six 3-axis setups) its phase 2
// segmentation and reachable area, and a greedy cover among the six axis setups. JSON:
//   {"count":N,"patches":[{"id":i,"facets":n,"area":a,"normal":[x,y,z],"neighbours":[...]}],
//    "setups":[{"name":"+z","reachable_area":a,"reachable_fraction":f,"segments":n}],"cover":["+z",...]}
// Areas are in mm^2 (--units says what the file's numbers are). Notes on an open or non-manifold mesh go to
// stderr.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/segment/coverage.hpp"
#include "rosmill/segment/setup_segmentation.hpp"

namespace rosmill::core::cli {
namespace {

struct SegmentArgs {
  std::string file, setups, units;
  double threshold = 0.4;
  size_t min_facets = 0;
  double min_area_fraction = segment::SizeRule().min_area_fraction;
  bool facets_given = false, json = false;
};

nlohmann::ordered_json patches_json(const segment::SurfacePatches& sp) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const segment::Patch& p : sp.patches())
    list.push_back({{"id", p.id},
                    {"facets", p.facet_count},
                    {"area", p.area},
                    {"normal", {p.normal.x(), p.normal.y(), p.normal.z()}},
                    {"neighbours", p.neighbours}});
  return list;
}

void warn_about_mesh(const std::string& file, const segment::MeshNotes& n) {
  if (n.open_edges)
    std::fprintf(stderr, "rosmill segment: %s: open mesh (%zu open edges): segmented as a surface\n", file.c_str(),
                 n.open_edges);
  if (n.nonmanifold_edges)
    std::fprintf(stderr, "rosmill segment: %s: %zu non-manifold edges\n", file.c_str(), n.nonmanifold_edges);
  if (n.inconsistent_edges)
    std::fprintf(stderr, "rosmill segment: %s: %zu edges between facets of opposite orientation\n", file.c_str(),
                 n.inconsistent_edges);
}

void run(const SegmentArgs& a) {
  StlReadOptions read;
  if (!a.units.empty()) read.units = parse_units(a.units, "--units");
  const Mesh mesh = read_stl(a.file, read);

  segment::SegmentOptions options;
  options.threshold = a.threshold;
  if (a.facets_given) {
    options.small.kind = segment::SizeRule::Kind::FacetCount;
    options.small.min_facets = a.min_facets;
  } else {
    options.small.min_area_fraction = a.min_area_fraction;
  }
  const segment::SurfacePatches sp = segment::segment_surface(mesh, options);
  warn_about_mesh(a.file, sp.notes());
  const segment::EgiSet egis(sp);
  const std::vector<segment::SetupFilter> setups =
      a.setups.empty() ? segment::axis_setups() : segment::parse_setups(a.setups);

  nlohmann::ordered_json setups_json = nlohmann::ordered_json::array();
  for (const segment::SetupFilter& s : setups) {
    const segment::SetupSegmentation seg = segment::segment_setup(egis, s);
    setups_json.push_back({{"name", s.name},
                           {"reachable_area", seg.reachable_area()},
                           {"reachable_fraction", seg.reachable_fraction()},
                           {"segments", seg.count()}});
  }
  nlohmann::ordered_json cover = nlohmann::ordered_json::array();
  for (const segment::SetupFilter& s : segment::greedy_axis_cover(egis)) cover.push_back(s.name);

  nlohmann::ordered_json j = {{"count", sp.count()}, {"patches", patches_json(sp)}, {"setups", setups_json},
                      {"cover", cover}};
  if (a.json) {
    std::cout << j.dump() << "\n";
    return;
  }
  std::printf("%s: %zu patches (%zu before recombination), %zu facets, area %.6g mm^2\n", a.file.c_str(),
              sp.count(), sp.notes().patches_before_recombination, mesh.face_count(), sp.total_area());
  for (const auto& p : j["patches"])
    std::printf("  patch %-5u %7zu facets  area %12.6g  normal % .3f % .3f % .3f  %zu neighbours\n",
                p["id"].get<unsigned>(), p["facets"].get<size_t>(), p["area"].get<double>(),
                p["normal"][0].get<double>(), p["normal"][1].get<double>(), p["normal"][2].get<double>(),
                p["neighbours"].size());
  for (const auto& s : setups_json)
    std::printf("  setup %-8s reaches %6.2f%% (%.6g mm^2) in %zu segments\n", s["name"].get<std::string>().c_str(),
                100.0 * s["reachable_fraction"].get<double>(), s["reachable_area"].get<double>(),
                s["segments"].get<size_t>());
  std::printf("  greedy axis cover: %s\n", cover.dump().c_str());
}

CommandRegistration reg([](CLI::App& app) {
  auto* cmd = app.add_subcommand("segment", "segment an STL part into surface patches and per-setup segments");
  auto args = std::make_shared<SegmentArgs>();
  cmd->add_option("FILE", args->file, "STL file")->required();
  cmd->add_option("--threshold", args->threshold,
                  "largest |n1 - n2| of unit normals across an edge inside a patch (default 0.4, ~23 deg)");
  auto* facets = cmd->add_option("--min-facets", args->min_facets, "patches with fewer facets merge");
  auto* fraction = cmd->add_option("--min-area-fraction", args->min_area_fraction,
                                   "patches with a smaller share of the area merge (default 1e-4)");
  facets->excludes(fraction);
  cmd->add_option("--setup", args->setups,
                  "comma-separated setups: +x,-x,+y,-y,+z,-z, 4axis:x|y|z, 5axis (default: the six 3-axis ones)");
  cmd->add_option("--units", args->units, "units of the file's numbers: mm (default), inch, m");
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->callback([args, facets] {
    args->facets_given = facets->count() > 0;
    run(*args);
  });
});

}  // namespace
}  // namespace rosmill::core::cli
