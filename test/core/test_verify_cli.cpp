// `rosmill verify` end to end: the JSON object the issue specifies, the deviation picture as a real PNG, and clear
// errors for bad inputs.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/testing/png_pixels.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"
#include "rosmill/verify/deviation_map.hpp"
#include "test_verify_programs.hpp"

using namespace verify_test;
using nlohmann::ordered_json;

namespace {

// Per test (ctest runs the cases of this file side by side, and they write files of the same names).
std::string temp(const std::string& name) {
  return ::testing::TempDir() + "/verify_cli_" + ::testing::UnitTest::GetInstance()->current_test_info()->name() +
         "_" + name;
}

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = temp(name);
  std::ofstream(path) << text;
  return path;
}

std::string cube_stl() {
  const std::string path = temp("cube.stl");
  write_stl(path, make_primitive("cube"));
  return path;
}

// The facing of the cube, then a 6 mm ball plunged 1.5 mm into the top at (30.1, 20.1): the gouge's line.
std::string gouge_program(int& gouge_line) {
  std::string program = facing();
  gouge_line = lines_of(program) + 4;
  program += "T2 M6\nG0 X30.1 Y20.1 Z62\nG1 Z61 F300\nG1 Z58.5 (the gouge)\nG0 Z70\nM30\n";
  return write_text("gouge.ngc", program);
}

const std::string kTools = "--tool 1=flat:10 --tool 2=ball:6";

}  // namespace

TEST(VerifyCli, JsonOfAGougingProgramHasTheIssuesKeysDepthPlaceAndLine) {
  int gouge_line = 0;
  const std::string program = gouge_program(gouge_line);
  const CliRun run = run_rosmill("verify " + cube_stl() + " " + program + " --stock 0,0,0,60,60,65 --resolution 0.2 " +
                                 kTools + " --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const ordered_json j = ordered_json::parse(run.out);
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"max_gouge_mm", "gouge_at", "gouge_line", "max_rest_mm", "mean_rest_mm",
                                            "scallop_mm", "unreached_area_mm2", "cells", "engagement", "seconds"}));
  EXPECT_NEAR(j["max_gouge_mm"].get<double>(), 1.5, 0.01);
  ASSERT_EQ(j["gouge_at"].size(), 3u);
  EXPECT_NEAR(j["gouge_at"][0].get<double>(), 30.1, 0.2);
  EXPECT_NEAR(j["gouge_at"][1].get<double>(), 20.1, 0.2);
  EXPECT_NEAR(j["gouge_at"][2].get<double>(), 58.5, 0.01);
  EXPECT_EQ(j["gouge_line"].get<int>(), gouge_line);
  EXPECT_LT(j["max_rest_mm"].get<double>(), 1e-4);  // the facing leaves the top exactly
  EXPECT_EQ(j["unreached_area_mm2"].get<double>(), 0.0);
  EXPECT_EQ(j["cells"].get<int>(), 300 * 300);
  EXPECT_GT(j["seconds"].get<double>(), 0.0);
}

TEST(VerifyCli, EngagementOfASlotAcrossTheCube) {
  // A 10 mm slot 5 deep across the cube's top (stock: the cube itself), plunged outside it at F500: 180 degrees
  // over the cube's 60 mm, removed 10 x 5 x 60 mm3 in the feed time of the 15 mm plunge and the 72 mm line.
  const std::string program = write_text("slot.ngc", "G21 G90 G17\nT1 M6\nG0 X-6 Y30 Z70\nG1 Z55 F500\nG1 X66\n"
                                                      "G0 Z70\nM30\n");
  const CliRun run = run_rosmill("verify " + cube_stl() + " " + program + " " + kTools + " --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const ordered_json e = ordered_json::parse(run.out)["engagement"];
  EXPECT_NEAR(e["max_deg"].get<double>(), 180.0, kEngagementToleranceDeg);
  EXPECT_NEAR(e["p95_deg"].get<double>(), 180.0, kEngagementToleranceDeg);
  EXPECT_NEAR(e["removed_mm3"].get<double>(), 10.0 * 5 * 60, 0.005 * 3000);
  EXPECT_NEAR(e["feed_min"].get<double>(), (15.0 + 72) / 500, 1e-9);
  EXPECT_NEAR(e["mrr_mm3_per_min"].get<double>(), 3000 / ((15.0 + 72) / 500), 0.005 * 3000 / (87.0 / 500));
  ASSERT_EQ(e["histogram"].size(), 18u);
  EXPECT_EQ(e["histogram_bin_deg"].get<double>(), 10.0);
  // In the last bin: the 55 mm where the whole leading half is in the cube, and the few tenths where 170 degrees
  // or more of it are, entering (R cos 85) and leaving (R (1 - cos 5)).
  EXPECT_NEAR(e["histogram"][17].get<double>(), 55 + 5 * std::cos(85 * M_PI / 180) + 5 * (1 - std::cos(5 * M_PI / 180)),
              0.25);
  EXPECT_NEAR(e["radial_mm"].get<double>(), 72.0, 1e-9);
  EXPECT_EQ(e["plunges"].get<int>(), 1);
  // The text output says it in a line.
  const CliRun text = run_rosmill("verify " + cube_stl() + " " + program + " " + kTools);
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("engagement max 180.0 deg, p95 180.0 deg"), std::string::npos) << text.out;
}

TEST(VerifyCli, JsonOfAToolpathFileGivesTheScallopAndNoGouge) {
  const std::string floor = temp("floor.stl"), toolpath = temp("raster.json");
  write_stl(floor, build_mesh(cube_corners(20)));
  write_toolpath_file(toolpath, {flat_raster(6, 1.0)});
  const CliRun run = run_rosmill("verify " + floor + " " + toolpath + " --stock 0,0,0,20,20,25 --resolution 0.02 --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const ordered_json j = ordered_json::parse(run.out);
  const double theory = 3 - std::sqrt(9 - 0.25);
  EXPECT_NEAR(j["scallop_mm"].get<double>(), theory, 0.02);
  EXPECT_LE(j["scallop_mm"].get<double>(), theory + 1e-5);
  EXPECT_EQ(j["max_gouge_mm"].get<double>(), 0.0);
  EXPECT_TRUE(j["gouge_at"].is_null());
  EXPECT_TRUE(j["gouge_line"].is_null());
  EXPECT_EQ(j["cells"].get<int>(), 1000 * 1000);
}

TEST(VerifyCli, ImageIsAPngMapWithItsLegend) {
  int gouge_line = 0;
  const std::string program = gouge_program(gouge_line), image = temp("deviation.png");
  std::remove(image.c_str());
  const CliRun run = run_rosmill("verify " + cube_stl() + " " + program + " --stock 0,0,0,60,60,65 --resolution 0.2 " +
                                 kTools + " --image " + image);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("line " + std::to_string(gouge_line)), std::string::npos) << run.out;
  const rosmill::testing::PngPixels png = rosmill::testing::read_png_pixels(image);
  // The 60 mm square at 800 pixels (13.3 a mm), the axes, the title and the legend beside.
  EXPECT_GT(png.width, 800 + 300);
  EXPECT_GT(png.height, 800);
  const std::vector<DeviationBand> bands = deviation_bands(0.01);
  for (const DeviationBand& b : bands) EXPECT_GT(png.count(b.colour), 28u * 20) << b.label;  // every swatch
  // The map: the top on the design, a crater of gouge colours about the ball's cap (radius 2.6 mm = 35 pixels).
  EXPECT_GT(png.count(bands[4].colour), 800u * 800u * 9 / 10);
  const size_t gouge = png.count(bands[1].colour) + png.count(bands[2].colour) + png.count(bands[3].colour);
  EXPECT_GT(gouge, 1800u);
  EXPECT_LT(gouge, 5400u);
}

TEST(VerifyCli, BadInputsGiveClearErrors) {
  const std::string cube = cube_stl();
  int line = 0;
  const std::string good = gouge_program(line);
  auto error = [&](const std::string& args) {
    const CliRun run = run_rosmill("verify " + args);
    EXPECT_EQ(run.status, 1) << args;
    EXPECT_TRUE(run.out.empty()) << run.out;
    return run.err;
  };
  EXPECT_NE(error(temp("missing.stl") + " " + good + " " + kTools).find("missing.stl"), std::string::npos);
  EXPECT_NE(error(cube + " " + temp("missing.ngc") + " " + kTools).find("missing.ngc: no such file"),
            std::string::npos);
  const std::string axis_a = write_text("axis_a.ngc", "G0 X0 Y0 Z70\nG1 X1 A2\n");
  EXPECT_NE(error(cube + " " + axis_a + " --tool ball:6").find("axis_a.ngc:2: axis A is not supported"),
            std::string::npos);
  const std::string t9 = write_text("t9.ngc", "T1 M6\nG0 X0 Y0 Z70\nT9 M6\n");
  EXPECT_NE(error(cube + " " + t9 + " " + kTools).find("t9.ngc:3: tool T9 is not in the tool table"), std::string::npos);
  const std::string no_tool = write_text("no_tool.ngc", "G0 X0 Y0 Z70\n");
  EXPECT_NE(error(cube + " " + no_tool + " " + kTools).find("no_tool.ngc:1: a move before any tool change"),
            std::string::npos);
  EXPECT_NE(error(cube + " " + good + " " + kTools + " --resolution 0").find("--resolution: the cell size must be"),
            std::string::npos);
  // A grid of 36e12 cells is refused at once, saying which cell size would do.
  const auto t0 = std::chrono::steady_clock::now();
  const std::string huge = error(cube + " " + good + " " + kTools + " --resolution 0.00001");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10.0);
  EXPECT_NE(huge.find("--resolution: a 60 x 60 mm area"), std::string::npos) << huge;
  EXPECT_NE(huge.find("use a cell of 0.012 mm or more"), std::string::npos) << huge;
  EXPECT_NE(error(cube + " " + good + " " + kTools + " --stock 10,10,0,20,20,70").find("does not hold the design"),
            std::string::npos);
  const std::string toolpath = temp("raster_t.json");
  write_toolpath_file(toolpath, {flat_raster(6, 1.0)});
  EXPECT_NE(error(cube + " " + toolpath + " --tool ball:6").find("--tool"), std::string::npos);
}
