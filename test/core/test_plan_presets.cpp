// Presets and the one entry point plan(request):
//  - config/presets.yaml reads, its templates name its presets, and bad tables are errors naming the entry;
//  - a preset fills only what the caller left unset; a template refuses a caller's tool;
//  - the cloud presets plan on a mesh too (grid-rough and step-error raster over the MeshSurface), without gouging
//    it beyond their tolerance, each toolpath named after its preset;
//  - the Surface's optional queries default to "nothing known" and "skip nothing";
//  - the cloud input step refuses bad options naming them; `rosmill plan --list` names everything.
#include <gtest/gtest.h>

#include "cli_run.hpp"
#include "error_of.hpp"
#include "plan_names.hpp"
#include "rosmill/cloud/cloud_input.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "test_plan_check.hpp"

using namespace rosmill::core;

TEST(PlanPresets, PackageTableHasThePapersStagesAndTemplate) {
  const PresetTable& t = test::package_presets();
  for (const char* name : {"cloud-rough", "cloud-semi", "cloud-finish"}) ASSERT_NE(t.find(name), nullptr) << name;
  EXPECT_EQ(t.find("cloud-rough")->strategy, "grid-rough");
  EXPECT_EQ(t.find("cloud-finish")->sampling, Sampling::StepError);
  EXPECT_EQ(t.find("cloud-finish")->tool.cutter.type, CutterType::BallEnd);
  EXPECT_DOUBLE_EQ(t.find("cloud-finish")->tool.cutter.diameter, 3.0);
  const PlanTemplate* all = t.find_template("cloud-all");
  ASSERT_NE(all, nullptr);
  EXPECT_EQ(all->stages, (std::vector<std::string>{"cloud-rough", "cloud-semi", "cloud-finish"}));
  for (const Preset& p : t.presets) EXPECT_NE(find_strategy(p.strategy), nullptr) << p.name;
}

TEST(PlanPresets, BadTablesAreErrorsNamingTheEntry) {
  const std::string tools =
      "tools:\n  - {id: 1, name: t, type: ball, diameter: 6, flute_length: 20, shank_diameter: 6, spindle_rpm: 1000,"
      " feed: 100, plunge_feed: 50, stepover: 1, stepdown: 1}\n";
  EXPECT_NE(error_of([&] { parse_presets(tools + "presets:\n  - {name: a, strategy: raster, tool: 7}\n", "p.yaml"); })
                .find("7"),
            std::string::npos);
  EXPECT_NE(error_of([&] { parse_presets(tools + "presets:\n  - {name: a, tool: 1}\n", "p.yaml"); }).find("strategy"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              parse_presets(tools + "presets:\n  - {name: a, strategy: raster, tool: 1, sampling: fine}\n", "p.yaml");
            }).find("fine"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              parse_presets(tools + "presets:\n  - {name: a, strategy: raster, tool: 1}\ntemplates:\n"
                                    "  - {name: b, stages: [a, c]}\n",
                            "p.yaml");
            }).find("'c'"),
            std::string::npos);
  // A stage that is not a name: the entry's own message, not yaml-cpp's "bad conversion".
  EXPECT_NE(error_of([&] {
              parse_presets(tools + "presets:\n  - {name: a, strategy: raster, tool: 1}\ntemplates:\n"
                                    "  - {name: b, stages: [{x: 1}]}\n",
                            "p.yaml");
            }).find("templates[0].stages: must list presets by name"),
            std::string::npos);
  const PresetTable ok = parse_presets(tools + "presets:\n  - {name: a, strategy: raster, tool: 1}\n", "p.yaml");
  EXPECT_EQ(ok.presets.size(), 1u);
  EXPECT_TRUE(std::isnan(ok.presets[0].stepover));
}

TEST(PlanPresets, PresetFillsOnlyWhatTheCallerLeftUnset) {
  const Preset& semi = *test::package_presets().find("cloud-semi");
  PlanParams given;
  given.tolerance = NAN;
  given.allowance = 0.1;
  PlanParams p = preset_params(semi, given);
  EXPECT_EQ(p.tool.name, semi.tool.name);
  EXPECT_DOUBLE_EQ(p.stepover, semi.stepover);
  EXPECT_DOUBLE_EQ(p.tolerance, semi.tolerance);
  EXPECT_DOUBLE_EQ(p.allowance, 0.1 + semi.allowance);
  EXPECT_EQ(p.sampling, Sampling::StepError);
  // A tool of the caller's brings its own stepover; a given tolerance stays.
  given.tool = default_tool(Cutter::ball(8));
  given.tolerance = 0.05;
  p = preset_params(semi, given);
  EXPECT_DOUBLE_EQ(p.tool.cutter.diameter, 8.0);
  EXPECT_TRUE(std::isnan(p.stepover));
  EXPECT_DOUBLE_EQ(p.tolerance, 0.05);
}

TEST(PlanPresets, CloudPresetsPlanOnAMeshWithoutGouging) {
  const Mesh dome = make_primitive("dome");
  PlanningRequest r;
  r.input.mesh = &dome;
  r.params.tolerance = NAN;
  r.presets = &test::package_presets();
  std::vector<PlanReport> reports;
  r.reports = &reports;
  for (const char* name : {"cloud-rough", "cloud-semi"}) {
    r.strategy = name;
    const Job job = plan(r);
    ASSERT_EQ(job.size(), 1u) << name;
    EXPECT_EQ(job[0].strategy, name);
    const Preset& p = *r.presets->find(name);
    // The grid rough keeps the allowance everywhere along its moves; the step-error raster's locations are drops
    // and its moves stay within the tolerance of the fine samples (a mesh answers no swept-move check).
    test::expect_no_gouge(job[0], dome, p.allowance, name, p.tolerance);
  }
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_GT(reports[0].levels, 1u);
  EXPECT_GT(reports[1].samples, 1000u);
  r.strategy = "cloud-all";
  r.params.tool = default_tool(Cutter::ball(6));
  EXPECT_NE(error_of([&] { plan(r); }).find("presets' tools"), std::string::npos);
  r.strategy = "no-such";
  const std::string unknown = error_of([&] { plan(r); });
  for (const char* name : {"raster", "grid-rough", "contour", "cloud-finish", "cloud-all"})
    EXPECT_NE(unknown.find(name), std::string::npos) << unknown;
}

TEST(PlanPresets, SurfaceQueriesDefaultToSampledSweepAndNoSkip) {
  // The dome (radius 50 on z = 0): a move above it is clear; one through its top finds the apex, 50 mm deep at
  // the middle of the move.
  const Mesh dome = make_primitive("dome");
  const MeshSurface s(dome);
  const Cutter ball = Cutter::ball(6);
  SweepHit hit = s.sweep(ball, Vec3(-100, 0, 60), Vec3(100, 0, 60), 0.01);
  EXPECT_EQ(hit.depth, 0.01);
  EXPECT_EQ(hit.at, 0.0);
  hit = s.sweep(ball, Vec3(-100, 0, 0), Vec3(100, 0, 0), 0.01);
  EXPECT_NEAR(hit.depth, 50.0, 1e-3);
  EXPECT_NEAR(hit.at, 0.5, 1e-3);
  EXPECT_FALSE(s.skips(0, 0, 3));
}

TEST(PlanPresets, CloudInputRefusesBadOptionsNamingThem) {
  CloudInputOptions o;
  o.orient = "sideways";
  EXPECT_NE(error_of([&] { cloud_prep_options(o, "~"); }).find("~orient"), std::string::npos);
  o = CloudInputOptions{};
  o.origin = "middle";
  EXPECT_NE(error_of([&] { cloud_prep_options(o, "--"); }).find("--origin"), std::string::npos);
  o = CloudInputOptions{};
  o.voxel = -1;
  EXPECT_NE(error_of([&] { cloud_prep_options(o, "--"); }).find("--voxel"), std::string::npos);
  o = CloudInputOptions{};
  o.holes = "fill";
  EXPECT_NE(error_of([&] { cloud_hole_policy(o, "--"); }).find("fill"), std::string::npos);
  o = CloudInputOptions{};
  o.origin = "keep";
  const CloudPrepOptions prep = cloud_prep_options(o, "--");
  EXPECT_FALSE(prep.origin_at_corner);
  EXPECT_EQ(prep.orientation, Orientation::AsIs);
}

TEST(PlanPresets, ListNamesStrategiesPresetsTemplatesAndTools) {
  const CliRun run = run_rosmill_shell("plan --list 2>&1");
  ASSERT_EQ(run.status, 0) << run.out;
  for (const char* name : {"raster", "waterline", "rough", "grid-rough", "contour", "cloud-rough", "cloud-semi",
                           "cloud-finish", "cloud-all", "10 mm flat end mill"})
    EXPECT_NE(run.out.find(name), std::string::npos) << name << " missing from: " << run.out;
}
