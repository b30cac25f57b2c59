// `rosmill info` end to end: the JSON object the issue specifies, for a mesh and a cloud, and errors on stderr.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"

using nlohmann::json;

namespace {

// Runs the rosmill tool with `args`; stdout is captured, stderr goes where `stderr_redirect` says.
CliRun rosmill(const std::string& args, const std::string& stderr_redirect = "2>/dev/null") {
  return run_rosmill_shell(args + " " + stderr_redirect);
}

}  // namespace

TEST(StlCli, InfoJsonOfAClosedBinaryMesh) {
  const CliRun run = rosmill("info --json " ROSMILL_TEST_DATA "/ktoolcav.stl --units inch");
  ASSERT_EQ(run.status, 0) << run.out;
  const json j = json::parse(run.out);
  EXPECT_EQ(j["kind"], "mesh");
  EXPECT_EQ(j["format"], "binary");
  EXPECT_EQ(j["triangles"], 4090);
  EXPECT_EQ(j["vertices"], 2041);
  EXPECT_EQ(j["closed"], true);
  EXPECT_EQ(j["open_edges"], 0);
  EXPECT_EQ(j["nonmanifold_edges"], 0);
  EXPECT_EQ(j["degenerate"], 0);
  // 4 x 1.625 x 3.3125 inch, printed in millimetres.
  EXPECT_NEAR(j["bbox"]["max"][0].get<double>() - j["bbox"]["min"][0].get<double>(), 4 * 25.4, 1e-4);
  EXPECT_NEAR(j["bbox"]["max"][1].get<double>() - j["bbox"]["min"][1].get<double>(), 1.625 * 25.4, 1e-4);
  EXPECT_GT(j["volume"].get<double>(), 0.0);
  EXPECT_NEAR(j["volume"].get<double>(), 18.1754 * 25.4 * 25.4 * 25.4, 0.01 * 18.1754 * 25.4 * 25.4 * 25.4);
  EXPECT_GT(j["area"].get<double>(), 0.0);
}

TEST(StlCli, InfoJsonOfAnOpenMeshHasNoVolume) {
  // mount_rush.stl is a relief: an open surface with non-manifold edges.
  const CliRun run = rosmill("info " ROSMILL_TEST_DATA "/mount_rush.stl --json");
  ASSERT_EQ(run.status, 0) << run.out;
  const json j = json::parse(run.out);
  EXPECT_EQ(j["format"], "binary");
  EXPECT_EQ(j["triangles"], 15592);
  EXPECT_EQ(j["open_edges"], 862);
  EXPECT_EQ(j["nonmanifold_edges"], 1645);
  EXPECT_EQ(j["closed"], false);
  EXPECT_GT(j["open_edges"].get<int>(), 0);
  EXPECT_FALSE(j.contains("volume"));
}

TEST(StlCli, InfoJsonOfAClosedAsciiMesh) {
  const CliRun run = rosmill("info " ROSMILL_TEST_DATA "/wheel_in_box.stl --json");
  ASSERT_EQ(run.status, 0) << run.out;
  const json j = json::parse(run.out);
  EXPECT_EQ(j["format"], "ascii");
  EXPECT_EQ(j["triangles"], 6102);
  EXPECT_EQ(j["closed"], true);
  EXPECT_GT(j["volume"].get<double>(), 0.0);
  EXPECT_LT(j["volume"].get<double>(), 200.0 * 200.0 * 50.0);  // inside its 200 x 200 x 50 mm box
}

TEST(StlCli, InfoJsonOfACloudInMetres) {
  const CliRun run = rosmill("info --json " ROSMILL_TEST_DATA "/pcl_table_scene_mug_stereo_textured.pcd");
  ASSERT_EQ(run.status, 0) << run.out;
  const json j = json::parse(run.out);
  EXPECT_EQ(j["kind"], "cloud");
  EXPECT_EQ(j["format"], "pcd");
  EXPECT_EQ(j["points"], 209280);
  EXPECT_FALSE(j.contains("triangles"));
  // A table-top stereo frame: about a metre deep, printed in millimetres.
  EXPECT_GT(j["bbox"]["max"][2].get<double>(), 500.0);
}

TEST(StlCli, InfoTextReport) {
  const CliRun run = rosmill("info " ROSMILL_TEST_DATA "/noether_wavy_mesh_with_hole.ply --units mm");
  ASSERT_EQ(run.status, 0);
  EXPECT_NE(run.out.find("cloud (ply)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("757"), std::string::npos) << run.out;
}

TEST(StlCli, InfoErrorsGoToStderrWithNonZeroStatus) {
  const CliRun missing = rosmill("info /nonexistent/part.stl", "2>&1 1>/dev/null");
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.out.find("/nonexistent/part.stl: no such file"), std::string::npos) << missing.out;
  const CliRun units = rosmill("info " ROSMILL_TEST_DATA "/ktoolcav.stl --units furlong", "2>&1 1>/dev/null");
  EXPECT_NE(units.status, 0);
  EXPECT_NE(units.out.find("furlong"), std::string::npos) << units.out;
}

// `info` on a small mesh runs in the front, which loads no thread library (its start-up is most of such a run);
// a large one goes to rosmill-info, which loads TBB. The two programs give the same report, byte for byte.
TEST(StlCli, TheFrontLoadsNoThreadLibraryAndReportsAsTheThreadedInfo) {
  const CliRun libraries = run_command("ldd " ROSMILL_CLI);
  ASSERT_EQ(libraries.status, 0);
  EXPECT_EQ(libraries.out.find("libtbb"), std::string::npos) << libraries.out;
  for (const char* file : {ROSMILL_TEST_DATA "/ktoolcav.stl", ROSMILL_TEST_DATA "/failedinpycam.stl"}) {
    SCOPED_TRACE(file);
    const CliRun front = rosmill(std::string("info --json ") + file);
    const CliRun threaded = run_command(std::string(ROSMILL_CLI "-info info --json ") + file + " 2>/dev/null");
    ASSERT_EQ(front.status, 0);
    ASSERT_EQ(threaded.status, 0);
    EXPECT_EQ(front.out, threaded.out);
  }
}
