// `rosmill plan CLOUD --strategy cloud-*` end to end: the seed's tools per stage, the mesh strategies' JSON, the
// toolpath file written with -o, and clear errors on stderr for bad options.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"

#include "rosmill/toolpath/toolpath_io.hpp"

using nlohmann::json;
using namespace rosmill::core;

namespace {

// `rosmill plan args`, stdout then stderr.
CliRun rosmill_plan(const std::string& args) { return run_rosmill_shell("plan " + args + " 2>&1"); }

const std::string kScan = ROSMILL_TEST_DATA "/snp_part_scan.ply";  // metres

}  // namespace

TEST(CloudCli, EachStageGivesTheMeshStrategiesJsonWithTheSeedsTool) {
  const struct {
    const char* strategy;
    const char* extra;
    size_t toolpaths;
    const char* tool;
  } cases[] = {
      {"cloud-rough", "", 1, "flat 10 mm (rough)"},
      {"cloud-semi", "--stepover 4", 1, "ball 5 mm (semi-finish)"},
      {"cloud-finish", "--stepover 3", 1, "ball 3 mm (finish)"},
      {"cloud-all", "--tolerance 0.05", 3, "flat 10 mm (rough) + ball 5 mm (semi-finish) + ball 3 mm (finish)"},
  };
  for (const auto& c : cases) {
    const CliRun run = rosmill_plan(kScan + " --strategy " + c.strategy + " " + c.extra + " --json");
    ASSERT_EQ(run.status, 0) << c.strategy << ": " << run.out;
    const json j = json::parse(run.out);
    EXPECT_EQ(j["strategy"], c.strategy);
    EXPECT_EQ(j["toolpaths"].get<size_t>(), c.toolpaths) << c.strategy;
    EXPECT_EQ(j["tool"], c.tool) << c.strategy;
    EXPECT_GT(j["moves"].get<size_t>(), 1000u) << c.strategy;
    EXPECT_GT(j["cutting_length"].get<double>(), 1000.0) << c.strategy;  // mm: the scan was read in metres
  }
}

TEST(CloudCli, ToolpathFileHoldsTheThreeStagesWithRapidsAtTheClearance) {
  const std::string out = "/tmp/rosmill_test_cloud_cli_" + std::to_string(::getpid()) + ".json";
  const CliRun run = rosmill_plan(kScan + " --strategy cloud-all --tolerance 0.05 --allowance 0.1 -o " + out);
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_NE(run.out.find("holes:"), std::string::npos) << "the preparation report is printed: " << run.out;
  const std::vector<Toolpath> job = read_toolpath_file(out);
  std::remove(out.c_str());
  ASSERT_EQ(job.size(), 3u);
  EXPECT_EQ(job[0].strategy, "cloud-rough");
  EXPECT_EQ(job[2].strategy, "cloud-finish");
  EXPECT_EQ(job[0].tool.cutter.type, CutterType::FlatEnd);
  EXPECT_EQ(job[2].tool.cutter.type, CutterType::BallEnd);
  for (const Toolpath& tp : job)
    for (const ToolpathPass& pass : tp.passes)
      for (const Move& m : pass.moves)
        if (m.type == MoveType::Rapid) {
          ASSERT_GE(m.to.z(), tp.clearance_z - 1e-9) << tp.strategy;
        }
}

TEST(CloudCli, BadOptionsAreClearErrors) {
  const struct {
    std::string args;
    const char* says;
  } cases[] = {
      {kScan + " --strategy cloud-all --tool ball:3", "--tool"},
      {kScan + " --strategy cloud-semi --holes maybe", "unknown hole policy 'maybe'"},
      {kScan + " --strategy cloud-rough --orient sideways", "--orient"},
      {kScan + " --strategy cloud-finish --tolerance -1", "tolerance"},
      // A cloud in millimetres read as metres (the default): refused with its size, not planned for hours.
      {ROSMILL_TEST_DATA "/noether_wavy_mesh_with_hole.ply --strategy cloud-rough", "check the cloud's units"},
      {"/nonexistent/cloud.pcd --strategy cloud-rough", "/nonexistent/cloud.pcd"},
  };
  for (const auto& c : cases) {
    const CliRun run = rosmill_plan(c.args);
    EXPECT_NE(run.status, 0) << c.args;
    EXPECT_NE(run.out.find(c.says), std::string::npos) << c.args << " said: " << run.out;
  }
}
