// `rosmill dropcutter` and `rosmill plan` end to end: the grid exactly as the issue defines it (origin at the
// box's min corner less the radius, nx and ny, row by row, z never below zmin, x y z lines, JSON fields), the
// plan JSON, and a clear error with a failing status for each bad option.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "cli_run.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/testing/reference_drop.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"

using nlohmann::json;
using namespace rosmill::core;

namespace {

// Runs the rosmill tool with `args`, stdout and stderr together.
CliRun run_cli(const std::string& args) { return run_rosmill_shell(args + " 2>&1"); }

const std::string kBox = ROSMILL_TEST_DATA "/pycam-textbox.stl";

}  // namespace

TEST(PlanCli, DropcutterGridAsSpecified) {
  const std::string out = ::testing::TempDir() + "rosmill_dropcutter_grid.xyz";
  const double S = 7.5, R = 3.0;
  const CliRun run = run_cli("dropcutter " + kBox + " --tool ball:6 --spacing 7.5 --threads 2 --json --out " + out);
  ASSERT_EQ(run.status, 0) << run.out;
  const json j = json::parse(run.out);
  const Mesh mesh = read_stl(kBox);
  const Box3& b = mesh.bbox;
  const long nx = static_cast<long>(std::floor((b.max.x() + R - (b.min.x() - R)) / S)) + 1;
  const long ny = static_cast<long>(std::floor((b.max.y() + R - (b.min.y() - R)) / S)) + 1;
  EXPECT_EQ(j["points"].get<long>(), nx * ny);
  EXPECT_GT(j["seconds"].get<double>(), 0.0);
  EXPECT_NEAR(j["points_per_second"].get<double>(), nx * ny / j["seconds"].get<double>(), 1e-6 * nx * ny);
  std::ifstream in(out);
  std::vector<std::array<double, 3>> pts;
  for (std::array<double, 3> p; in >> p[0] >> p[1] >> p[2];) pts.push_back(p);
  ASSERT_EQ(static_cast<long>(pts.size()), nx * ny);
  for (long row = 0; row < ny; ++row)
    for (long col = 0; col < nx; ++col) {
      const auto& p = pts[row * nx + col];  // y outer, x inner
      ASSERT_NEAR(p[0], b.min.x() - R + col * S, 1e-6) << row << " " << col;
      ASSERT_NEAR(p[1], b.min.y() - R + row * S, 1e-6) << row << " " << col;
      ASSERT_GE(p[2], b.min.z() - 1e-9);
    }
  // Every 7th point against the independent reference (the file holds 10 significant digits).
  for (size_t k = 0; k < pts.size(); k += 7) {
    const auto& p = pts[k];
    const double ref = std::max(reference_drop(Cutter::ball(6), mesh, p[0], p[1]), b.min.z());
    EXPECT_NEAR(p[2], ref, 1e-6) << p[0] << " " << p[1];
  }
}

TEST(PlanCli, PlanJsonFields) {
  for (const char* strategy : {"raster", "waterline", "rough"}) {
    const CliRun run = run_cli("plan " + kBox + " --strategy " + strategy +
                               " --tool flat:6 --stepover 5 --stepdown 5 --allowance 0.2 --tolerance 0.01 --json");
    ASSERT_EQ(run.status, 0) << strategy << ": " << run.out;
    const json j = json::parse(run.out);
    EXPECT_EQ(j["strategy"], strategy);
    EXPECT_GT(j["moves"].get<long>(), 10) << strategy;
    EXPECT_GT(j["cutting_length"].get<double>(), 100.0) << strategy;
    EXPECT_GT(j["rapid_length"].get<double>(), 0.0) << strategy;
    EXPECT_GT(j["estimated_seconds"].get<double>(), 0.0) << strategy;
    EXPECT_GT(j["seconds"].get<double>(), 0.0) << strategy;
  }
}

// A tool number resolves from any folder: the working folder's config/tools.yaml when it has one, else the
// package's own table.
TEST(PlanCli, ToolNumbersResolveFromAnyFolder) {
  const std::string dir = ::testing::TempDir() + "rosmill_elsewhere_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/config");
  const std::string args = "plan " + kBox + " --strategy raster --tool 2 --stepover 5 --json 2>&1";
  CliRun run = run_rosmill_in(dir, args);
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_EQ(json::parse(run.out)["tool"], "6 mm ball end mill (finishing)");
  std::ofstream(dir + "/config/tools.yaml")
      << "tools:\n  - {id: 2, name: \"cell's 4 mm flat\", type: flat, diameter: 4, flute_length: 12, "
         "shank_diameter: 4, spindle_rpm: 12000, feed: 800, plunge_feed: 200, stepover: 1, stepdown: 1}\n";
  run = run_rosmill_in(dir, args);
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_EQ(json::parse(run.out)["tool"], "cell's 4 mm flat");
  std::filesystem::remove_all(dir);
}

TEST(PlanCli, BadOptionsFailWithAClearError) {
  const std::string tools = " --tools " ROSMILL_SOURCE_DIR "/config/tools.yaml";
  const std::pair<std::string, std::string> cases[] = {
      {"plan " + kBox + " --strategy raster --stepover -1", "stepover"},
      {"plan " + kBox + " --strategy raster --stepover nan", "--stepover"},
      {"plan " + kBox + " --strategy raster --tolerance nan", "--tolerance"},
      {"plan " + kBox + " --strategy raster --angle inf", "--angle"},
      {"plan " + kBox + " --strategy raster --allowance -2", "allowance"},
      {"plan " + kBox + " --strategy raster --tool flat:0", "diameter"},
      {"plan " + kBox + " --strategy raster --tool 999" + tools, "999"},
      {"plan " + kBox + " --strategy nosuch", "nosuch"},
      {"dropcutter " + kBox + " --tool ball:0 --spacing 1", "diameter"},
      {"dropcutter " + kBox + " --tool bull:6:4 --spacing 1", "corner radius"},
      {"dropcutter " + kBox + " --tool ball:6 --spacing 0", "--spacing"},
      {"dropcutter " + kBox + " --tool ball:6 --spacing nan", "--spacing"},
      {"dropcutter " + kBox + " --tool ball:6 --spacing -2", "--spacing"},
      {"dropcutter " + kBox + " --tool drill:6 --spacing 1", "drill:6"},
  };
  for (const auto& [args, word] : cases) {
    const CliRun run = run_cli(args);
    EXPECT_NE(run.status, 0) << args;
    EXPECT_NE(run.out.find("error"), std::string::npos) << args << ": " << run.out;
    EXPECT_NE(run.out.find(word), std::string::npos) << args << ": " << run.out;
  }
}

// --place plans the design where a registration found it, tilted out of the table's plane too (a work offset can
// only turn a program about Z): no cutter location of the raster gouges the placed part (the reference
// branch-and-bound over every triangle), the passes lie over the placed part, and an ambiguous registration or a
// cloud is refused with the reason.
TEST(PlanCli, PlaceRunsThePlanOnTheRegisteredPose) {
  const Mesh design = read_stl(kBox);
  Eigen::Matrix4d pose = Eigen::Matrix4d::Identity();
  pose.topLeftCorner<3, 3>() = (Eigen::AngleAxisd(10 * M_PI / 180, Vec3::UnitX()) *
                                Eigen::AngleAxisd(25 * M_PI / 180, Vec3::UnitZ())).toRotationMatrix();
  pose.topRightCorner<3, 1>() = Vec3(120, -40, 15);
  const auto registration = [&](bool ambiguous) {
    const std::string path = ::testing::TempDir() + (ambiguous ? "place_ambiguous.json" : "place.json");
    json rows = json::array();
    for (int r = 0; r < 4; ++r) rows.push_back({pose(r, 0), pose(r, 1), pose(r, 2), pose(r, 3)});
    std::ofstream(path) << json{{"transform", rows}, {"rms", 0.02}, {"inlier_share", 1.0}, {"ambiguous", ambiguous},
                                {"ambiguity", ambiguous ? "2 distinct poses fit about equally" : ""}}
                               .dump();
    return path;
  };
  const std::string out = ::testing::TempDir() + "placed_raster.json";
  const CliRun run = run_cli("plan " + kBox + " --strategy raster --tool ball:6 --stepover 3 --tolerance 0.01 --place " +
                             registration(false) + " -o " + out);
  ASSERT_EQ(run.status, 0) << run.out;
  const Mesh placed = transformed_mesh(design, pose, "test");
  const Cutter ball = Cutter::ball(6);
  size_t checked = 0;
  Box3 covered;
  for (const Toolpath& tp : read_toolpath_file(out))
    for (const ToolpathPass& pass : tp.passes)
      for (size_t k = 0; k < pass.moves.size(); ++k) {
        const Move& m = pass.moves[k];
        if (m.type == MoveType::Rapid) continue;
        covered.add(m.to);
        if (k % 7) continue;  // the gouge check on every seventh location: a spread sample
        EXPECT_FALSE(reference_gouges(ball, placed, m.to, 0.011)) << "gouge at " << m.to.transpose();
        ++checked;
      }
  EXPECT_GT(checked, 200u);
  // The passes run over the placed part's box (not the design's at the origin).
  EXPECT_LT(std::abs(covered.min.x() - placed.bbox.min.x()), 6.0);
  EXPECT_LT(std::abs(covered.max.y() - placed.bbox.max.y()), 6.0);
  EXPECT_GT(covered.max.z(), placed.bbox.max.z() - 1.0);  // over the tilted top, not at the design's height
  std::printf("placed part box z %.3f..%.3f, the raster's z %.3f..%.3f, %zu locations checked\n", placed.bbox.min.z(),
              placed.bbox.max.z(), covered.min.z(), covered.max.z(), checked);

  const CliRun ambiguous = run_cli("plan " + kBox + " --strategy raster --place " + registration(true));
  EXPECT_NE(ambiguous.status, 0);
  EXPECT_NE(ambiguous.out.find("ambiguous"), std::string::npos) << ambiguous.out;
  const CliRun cloud = run_cli("plan " + std::string(ROSMILL_TEST_DATA) + "/pcl_milk.pcd --strategy cloud-rough "
                               "--place " + registration(false));
  EXPECT_NE(cloud.status, 0);
  EXPECT_NE(cloud.out.find("--place"), std::string::npos) << cloud.out;
}

// An inline tool carries its number in the controller's tool table: `flat:10@7` is written T7 M6 and G43 H7, never
// T0 (which empties LinuxCNC's spindle), and `rosmill verify` reads the program back with the same spec. Without a
// number no program is written, and the message says how to give one.
TEST(PlanCli, InlineToolsAreWrittenWithTheirNumber) {
  const std::string dir = ::testing::TempDir() + "rosmill_inline_tool_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const std::string cavity = dir + "/cavity.stl", program = dir + "/a.ngc";
  ASSERT_EQ(run_cli("primitive cavity -o " + cavity).status, 0);
  const std::string plan = "plan " + cavity + " --strategy raster --stepover 4 --no-limits ";
  CliRun r = run_cli(plan + "--tool flat:10 -o " + program);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("has no number in the controller's tool table: give it as flat:10@N"), std::string::npos)
      << r.out;
  EXPECT_FALSE(std::filesystem::exists(program));
  r = run_cli(plan + "--tool flat:10@7 -o " + program);
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream in(program);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\nT7 M6\nG43 H7\n"), std::string::npos);
  EXPECT_EQ(text.find("T0"), std::string::npos);
  r = run_cli("verify " + cavity + " " + program + " --tool flat:10@7 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(json::parse(r.out)["max_gouge_mm"], 0.0);
  r = run_cli("verify " + cavity + " " + program + " --tool flat:10");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("tool T7 is not in the tool table: give it as --tool CUTTER@7"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}
