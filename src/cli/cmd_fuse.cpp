// rosmill fuse VIEW1 POSE1 [VIEW2 POSE2 ...] -o fused.pcd [--units U] [--voxel MM] [--outliers K] [--no-refine]
//   [--rounds N] [--max-correction MM] [--pose-error MM] [--pose-error-deg DEG] [--json]: views (PCD, PLY) with
// their sensor poses (YAML files, see include/rosmill/scan/pose_file.hpp) brought into one frame, refined by ICP,
// fused, filtered, written as PCD. A view whose correction exceeds the stated pose error keeps its given pose
// ("applied": false); a view whose pose the overlap fixes only weakly is corrected along the well-fixed motions only,
// keeping its given pose along the weak ones ("locked": true), and marked ("ambiguous": true, "weak" naming the
// directions, "reason"). Either way the cloud is still written and the command exits with status 3.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/scan/pose_file.hpp"
#include "rosmill/scan/report_json.hpp"
#include "rosmill/scan/view_fusion.hpp"

namespace rosmill::core::cli {
namespace {

struct FuseArgs {
  std::vector<std::string> inputs;
  std::string out, units = "m";
  bool no_refine = false, json = false;
  scan::FusionOptions options;
};

void run(const FuseArgs& a) {
  if (a.inputs.size() % 2 != 0)
    throw Error("rosmill fuse", "views come in pairs VIEW POSE; got " + std::to_string(a.inputs.size()) + " files");
  CloudReadOptions read;
  read.units = parse_units(a.units, "--units");
  std::vector<scan::ScanView> views;
  for (size_t i = 0; i < a.inputs.size(); i += 2) {
    scan::ScanView v;
    v.name = a.inputs[i];
    v.cloud = read_cloud(a.inputs[i], read);
    v.pose = scan::read_pose_file(a.inputs[i + 1]);
    views.push_back(std::move(v));
  }
  scan::FusionOptions o = a.options;
  o.refine = !a.no_refine;
  scan::FusionReport r;
  const PointCloud fused = scan::fuse_views(views, o, &r);
  write_cloud(a.out, fused, read.units);
  if (a.json) {
    nlohmann::ordered_json j = {{"views", views.size()}, {"points_in", r.points_in}, {"points_out", r.points_out},
                                {"seconds", r.seconds}, {"output", a.out}};
    j["withheld"] = r.withheld;
    j["ambiguous"] = r.ambiguous;
    j["corrections"] = nlohmann::ordered_json::array();
    for (size_t i = 0; i < r.corrections.size(); ++i) {
      const scan::ViewCorrection& c = r.checks[i];
      nlohmann::ordered_json v = {{"view", views[i].name},
                                  {"translation_mm", translation_length(r.corrections[i])},
                                  {"rotation_deg", rotation_angle_deg(r.corrections[i])},
                                  {"overlap", r.overlaps.empty() ? 1.0 : r.overlaps[i]},
                                  {"applied", c.applied},
                                  {"ambiguous", c.ambiguous},
                                  {"exceeds_pose_error", c.exceeds_pose_error},
                                  {"locked", c.locked},
                                  {"found_moved_mm", c.moved_mm},
                                  {"found_turned_deg", c.turned_deg},
                                  {"reason", c.reason}};
      if (i > 0 && !a.no_refine) {
        const nlohmann::ordered_json info = scan::pose_information_json(c.information);
        v["weak"] = info["weak"];
        v["degrees_of_freedom"] = info;
      }
      j["corrections"].push_back(v);
    }
    std::cout << j.dump() << std::endl;
  } else {
    std::printf("%zu views, %zu points in, %zu out, %.3f s -> %s\n", views.size(), r.points_in, r.points_out, r.seconds,
                a.out.c_str());
    for (size_t i = 0; i < r.corrections.size(); ++i)
      std::printf("  %s: pose corrected by %.4f mm, %.4f deg; overlap %.3f%s%s\n", views[i].name.c_str(),
                  translation_length(r.corrections[i]), rotation_angle_deg(r.corrections[i]),
                  r.overlaps.empty() ? 1.0 : r.overlaps[i], r.checks[i].applied ? (r.checks[i].ambiguous ? "; AMBIGUOUS: " : "") : "; correction WITHHELD: ",
                  r.checks[i].reason.c_str());
  }
  if (r.withheld > 0 || r.ambiguous > 0) {
    std::fprintf(stderr, "rosmill fuse: %zu view correction(s) withheld (beyond the stated pose error: the view keeps "
                 "its given pose), %zu view(s) ambiguous (the overlap fixes a direction only weakly): see the report; "
                 "exit status 3\n", r.withheld, r.ambiguous);
    throw CLI::RuntimeError(3);
  }
}

CommandRegistration reg([](CLI::App& app) {
  auto* cmd = app.add_subcommand("fuse", "fuse scan views with their sensor poses into one cloud");
  auto a = std::make_shared<FuseArgs>();
  cmd->add_option("VIEW_POSE", a->inputs, "VIEW1 POSE1 VIEW2 POSE2 ...: a cloud (PCD, PLY) and its pose (YAML)")
      ->required();
  cmd->add_option("-o,--out", a->out, "the fused cloud (PCD)")->required();
  cmd->add_option("--units", a->units, "units of the views' numbers and of the output (default m)")
      ->check(CLI::IsMember({"mm", "inch", "in", "m"}));
  cmd->add_option("--voxel", a->options.voxel, "mm: voxel grid leaf of the fused cloud (0: off)");
  cmd->add_option("--outliers", a->options.outlier_neighbours, "statistical outlier removal over K neighbours (0: off)");
  cmd->add_option("--rounds", a->options.rounds, "refinement rounds (1: each view onto those before it)");
  cmd->add_option("--max-correction", a->options.max_correction, "mm: how far a view's pose may be off (5)");
  cmd->add_option("--pose-error", a->options.pose_error_mm,
                  "mm: how far the given poses may be off; a larger correction is withheld (10)");
  cmd->add_option("--pose-error-deg", a->options.pose_error_deg,
                  "degrees: how far the given poses may be turned off; a larger correction is withheld (2)");
  cmd->add_flag("--no-refine", a->no_refine, "trust the poses: no ICP between the views");
  cmd->add_flag("--json", a->json, "print one JSON object");
  cmd->callback([a] { run(*a); });
});

}  // namespace
}  // namespace rosmill::core::cli
