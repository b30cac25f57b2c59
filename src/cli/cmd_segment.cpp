// rosmill segment FILE [--threshold 0.4] [--min-facets N | --min-area-fraction F] [--setup LIST] [--units U]
//                      [--setups auto [--tool ID|SPEC] [--tools FILE] [--held-face DIR] [--min-gain F]] [--json]
// Phase 1 surface patches of an STL part, then for each setup (default: the six 3-axis setups) its phase 2
// segmentation and reachable area, and a greedy cover among the six axis setups. JSON:
//   {"count":N,"patches":[{"id":i,"facets":n,"area":a,"normal":[x,y,z],"neighbours":[...]}],
//    "setups":[{"name":"+z","reachable_area":a,"reachable_fraction":f,"segments":n}],"cover":["+z",...]}
// With --setups auto the setups chosen instead (setups/setup_choice.hpp): what the tool, its shank and its holder
// reach from each candidate direction, the fewest setups that reach the most of the part:
//   "setups":[{"direction":[x,y,z],"name":"+Z","reachable_area":a,"assigned_area":a,
//              "segments":[{"patch":p,"area":a,"normal":[x,y,z]}]}],
//   "unreachable_area":a, "unreachable":[{"patch":p,"reason":"held","area":a,"centroid":[..],"normal":[..]}],
//   "candidates":[...], "search":{"exhaustive":true,"subsets":n,...}
// Areas are in mm^2 (--units says what the file's numbers are). Notes on an open or non-manifold mesh go to
// stderr.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "config_file.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/setups/setup_choice.hpp"
#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/segment/coverage.hpp"
#include "rosmill/segment/setup_segmentation.hpp"

namespace rosmill::core::cli {
namespace {

struct SegmentArgs {
  std::string file, setups, units, choose, tool = "2", tools, held_face;
  double min_gain = 0.005, max_angle = 90;
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

// No "-0" in the output: a direction of -X reads [-1, 0, 0].
nlohmann::ordered_json vec(const Vec3& v) { return {v.x() + 0.0, v.y() + 0.0, v.z() + 0.0}; }

// The setups chosen for the part: --setups auto.
nlohmann::ordered_json chosen_setups_json(const Mesh& mesh, const segment::SurfacePatches& sp, const SegmentArgs& a) {
  setups::ChoiceOptions o;
  const ToolTable tools = read_tool_table(a.tools.empty() ? default_config("tools.yaml") : a.tools);
  o.tool = resolve_tool(a.tool, &tools);
  o.min_gain_share = a.min_gain;
  o.max_angle_deg = a.max_angle;
  if (!a.held_face.empty()) o.held_face = named_setup(a.held_face, "--held-face").tool_axis;
  const setups::SetupChoice c = setups::choose_setups(mesh, sp, o);
  nlohmann::ordered_json chosen = nlohmann::ordered_json::array(), places = nlohmann::ordered_json::array(),
                         candidates = nlohmann::ordered_json::array();
  for (const setups::ChosenSetup& s : c.setups) {
    nlohmann::ordered_json segments = nlohmann::ordered_json::array();
    for (const setups::SegmentShare& g : s.segments)
      segments.push_back({{"patch", g.patch}, {"area", g.area}, {"normal", vec(g.normal)}});
    chosen.push_back({{"direction", vec(s.direction)}, {"name", s.name}, {"source", s.source},
                      {"reachable_area", s.reachable_area}, {"assigned_area", s.assigned_area},
                      {"segments", segments}});
  }
  for (const setups::Unreached& u : c.unreachable)
    places.push_back({{"patch", u.patch}, {"reason", u.reason}, {"area", u.area}, {"centroid", vec(u.centroid)},
                      {"normal", vec(u.normal)}});
  for (size_t k = 0; k < c.candidates.size(); ++k) {
    nlohmann::ordered_json j = {{"direction", vec(c.candidates[k].direction)}, {"name", c.candidates[k].name},
                                {"source", c.candidates[k].source}, {"reachable_area", c.candidate_area[k]}};
    if (!c.candidate_refused[k].empty()) j["refused"] = c.candidate_refused[k];
    candidates.push_back(j);
  }
  return {{"tool", o.tool.name},
          {"area", c.total_area},
          {"setups", chosen},
          {"machined_area", c.machined_area},
          {"unreachable_area", c.unreachable_area},
          {"unreachable", places},
          {"candidates", candidates},
          {"search", {{"exhaustive", c.exhaustive}, {"subsets", c.subsets}, {"best_cover", c.best_cover},
                      {"samples", c.samples.size()}, {"reach_seconds", c.reach_seconds},
                      {"search_seconds", c.search_seconds}}}};
}

void print_chosen(const std::string& file, const nlohmann::ordered_json& j) {
  std::printf("%s: %zu setups for the %s, %.6g of %.6g mm^2 machined\n", file.c_str(), j["setups"].size(),
              j["tool"].get<std::string>().c_str(), j["machined_area"].get<double>(), j["area"].get<double>());
  for (const auto& s : j["setups"])
    std::printf("  setup %-7s direction % .3f % .3f % .3f  reaches %10.6g mm^2, machines %10.6g in %zu segments (%s)\n",
                s["name"].get<std::string>().c_str(), s["direction"][0].get<double>(),
                s["direction"][1].get<double>(), s["direction"][2].get<double>(), s["reachable_area"].get<double>(),
                s["assigned_area"].get<double>(), s["segments"].size(), s["source"].get<std::string>().c_str());
  std::printf("  unreachable %.6g mm^2\n", j["unreachable_area"].get<double>());
  for (const auto& u : j["unreachable"])
    std::printf("    %-11s %10.6g mm^2 on patch %u around % .2f % .2f % .2f\n", u["reason"].get<std::string>().c_str(),
                u["area"].get<double>(), u["patch"].get<unsigned>(), u["centroid"][0].get<double>(),
                u["centroid"][1].get<double>(), u["centroid"][2].get<double>());
  const auto& s = j["search"];
  std::printf("  %s search over %zu candidates: %llu sets compared (reach %.3f s, search %.3f s)\n",
              s["exhaustive"].get<bool>() ? "exhaustive" : "greedy", j["candidates"].size(),
              static_cast<unsigned long long>(s["subsets"].get<uint64_t>()), s["reach_seconds"].get<double>(),
              s["search_seconds"].get<double>());
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
  if (!a.choose.empty()) {
    if (a.choose != "auto") throw Error("--setups", "expected auto, got '" + a.choose + "'");
    const nlohmann::ordered_json j = chosen_setups_json(mesh, sp, a);
    if (a.json) {
      nlohmann::ordered_json out = {{"count", sp.count()}, {"patches", patches_json(sp)}};
      for (const auto& [key, value] : j.items()) out[key] = value;
      std::cout << out.dump() << "\n";
    } else {
      print_chosen(a.file, j);
    }
    return;
  }
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
  cmd->add_option("--setups", args->choose, "auto: choose the setups that reach the most of the part with the fewest");
  cmd->add_option("--tool", args->tool, "with --setups auto: the tool whose reach counts (id or ball:D etc.; default 2)");
  cmd->add_option("--tools", args->tools, "tool table (default config/tools.yaml here, else the package's)");
  cmd->add_option("--held-face", args->held_face, "with --setups auto: the face the part is held by (+Z, -Z, ...)");
  cmd->add_option("--min-gain", args->min_gain, "with --setups auto: least share of the area a setup must add (0.005)");
  cmd->add_option("--max-angle", args->max_angle, "with --setups auto: largest angle of a reached face's normal (90)");
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->callback([args, facets] {
    args->facets_given = facets->count() > 0;
    run(*args);
  });
});

}  // namespace
}  // namespace rosmill::core::cli
