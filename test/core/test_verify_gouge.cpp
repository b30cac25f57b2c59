// Gouges are caught with their depth, place and line; raster finishing leaves the theoretical scallop.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "rosmill/geometry/primitives.hpp"
#include "rosmill/verify/gcode_reader.hpp"
#include "rosmill/verify/verify.hpp"
#include "test_verify_programs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::verify;
using namespace rosmill::core::stock;
using namespace verify_test;

namespace {

VerifyResult run(const std::string& program, const std::vector<std::string>& tools, double resolution) {
  VerifyOptions o;
  o.resolution = resolution;
  return verify_program(make_primitive("cube"), parse_gcode(program, "t.ngc", tool_setup(tools)),
                        box(0, 0, 0, 60, 60, 65), o);
}

}  // namespace

TEST(VerifyGouge, CleanFacingHasNoGouge) {
  const VerifyResult r = run(facing(), {"1=flat:10"}, 0.25);
  EXPECT_FALSE(r.report.gouged);
  EXPECT_EQ(r.report.max_gouge_mm, 0.0);
  EXPECT_LT(r.report.max_rest_mm, 1e-4);
  EXPECT_EQ(r.report.unreached_area_mm2, 0.0);
}

TEST(VerifyGouge, BallPlungeIsCaughtWithDepthPlaceAndLine) {
  std::string program = facing();
  const int plunge_line = lines_of(program) + 4;  // after T2 M6, G0 and G1 Z61
  program += "T2 M6\nG0 X30.1 Y20.1 Z62\nG1 Z61 F300\nG1 Z58.5 (the gouge)\nG0 Z70\nM30\n";
  const double res = 0.2;
  const VerifyResult r = run(program, {"1=flat:10", "2=ball:6"}, res);
  ASSERT_TRUE(r.report.gouged);
  EXPECT_NEAR(r.report.max_gouge_mm, 1.5, 0.01);  // the cell centre nearest the tip: within 0.1 mm, 2 um higher
  EXPECT_NEAR(r.report.gouge_at.x(), 30.1, res);
  EXPECT_NEAR(r.report.gouge_at.y(), 20.1, res);
  EXPECT_NEAR(r.report.gouge_at.z(), 58.5, 0.01);
  EXPECT_EQ(r.report.gouge_source, static_cast<uint32_t>(plunge_line));
  // The crater is a spherical cap of the ball: 1.5 deep, radius sqrt(2 R h - h^2) at the top.
  const double cap = std::sqrt(2 * 3 * 1.5 - 1.5 * 1.5);
  EXPECT_NEAR(r.report.gouge_cells * res * res, M_PI * (cap * cap - 0.01 * 6), 1.0);
}

TEST(VerifyGouge, SlotGougeNamesTheFirstLineThatCutDeepest) {
  std::string program = facing();
  const int slot_line = lines_of(program) + 3;
  program += "G0 X10 Y40 Z62\nG1 Z59 F300\nG1 X50\nG1 Z59.5\nG1 X10\nG0 Z70\n";
  const VerifyResult r = run(program, {"1=flat:10"}, 0.25);
  ASSERT_TRUE(r.report.gouged);
  EXPECT_NEAR(r.report.max_gouge_mm, 1.0, 1e-4);
  EXPECT_NEAR(r.report.gouge_at.y(), 40, 5 + 0.25);
  EXPECT_GE(r.report.gouge_at.x(), 5 - 0.25);
  EXPECT_LE(r.report.gouge_at.x(), 55 + 0.25);
  // The plunge (line slot_line - 1) cut the disc at x 10 first; the cell reported is the first to reach -1.
  EXPECT_TRUE(r.report.gouge_source == static_cast<uint32_t>(slot_line) ||
              r.report.gouge_source == static_cast<uint32_t>(slot_line - 1));
}

TEST(VerifyGouge, RapidIntoMaterialIsCounted) {
  const std::string program = facing() + "G0 X30 Y30 Z55\nG0 Z70\n";
  const VerifyResult r = run(program, {"1=flat:10"}, 0.5);
  EXPECT_GT(r.report.rapid_cut_cells, 0u);
  EXPECT_EQ(r.report.first_rapid_cut_source, static_cast<uint32_t>(lines_of(facing()) + 1));
  EXPECT_NEAR(r.report.max_gouge_mm, 5.0, 1e-4);
}

TEST(VerifyGouge, RasterWithABallLeavesTheTheoreticalScallop) {
  const Mesh floor = build_mesh(cube_corners(20));
  for (const double s : {1.0, 2.0}) {
    const double R = 3, res = 0.02, theory = R - std::sqrt(R * R - 0.25 * s * s);
    VerifyOptions o;
    o.resolution = res;
    const VerifyResult r = verify_program(floor, program_from_job({flat_raster(2 * R, s)}), box(0, 0, 0, 20, 20, 25), o);
    EXPECT_NEAR(r.report.scallop_theory_mm, theory, 1e-12);
    EXPECT_NEAR(r.report.scallop_mm, theory, res) << "stepover " << s;
    EXPECT_LE(r.report.scallop_mm, theory + 1e-5);
    EXPECT_FALSE(r.report.gouged);
    EXPECT_NEAR(r.report.max_rest_mm, theory, res);
    // Mean of R - sqrt(R^2 - y^2) over y uniform in [0, s/2].
    const double h = 0.5 * s;
    const double mean = R - (0.5 * (h * std::sqrt(R * R - h * h) + R * R * std::asin(h / R))) / h;
    EXPECT_NEAR(r.report.mean_rest_mm, mean, 2e-3);
  }
}
