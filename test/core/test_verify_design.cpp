// Verification of whole programs on the seed primitives, with results known in closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "rosmill/geometry/primitives.hpp"
#include "rosmill/stock/design_height.hpp"
#include "rosmill/verify/gcode_reader.hpp"
#include "rosmill/verify/verify.hpp"
#include "test_verify_programs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::verify;
using namespace rosmill::core::stock;
using namespace verify_test;

namespace {

ToolSetup tools(const std::string& spec) { return tool_setup({spec}); }

// A zig-zag raster along x at height z: lines y = y0, y0 + step, ... up to y1 (inclusive), from x0 to x1.
std::string raster(double x0, double x1, double y0, double y1, double step, double z) {
  std::ostringstream g;
  g << "G0 X" << x0 << " Y" << y0 << " Z" << z + 20 << "\nG1 Z" << z << " F500\n";
  const int n = static_cast<int>(std::floor((y1 - y0) / step + 1e-9));
  for (int k = 0; k <= n; ++k) {
    const double y = y0 + k * step;
    g << "G1 Y" << y << "\nG1 X" << (k % 2 ? x0 : x1) << "\n";
  }
  return g.str();
}

size_t cells_with_deviation_above(const DeviationGrid& g, double v) {
  size_t n = 0;
  for (float d : g.deviation) n += d > v;
  return n;
}

}  // namespace

TEST(VerifyDesign, DesignHeightsOfTheCubeAndDome) {
  const Mesh cube = make_primitive("cube");
  const GridSpec g = GridSpec::covering(Vec2(-10, -10), Vec2(70, 70), 0.5);
  const std::vector<float> z = design_heights(cube, g, 0.0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const bool inside = g.cx(i) > 0 && g.cx(i) < 60 && g.cy(j) > 0 && g.cy(j) < 60;
      ASSERT_FLOAT_EQ(z[g.index(i, j)], inside ? 60.0f : 0.0f);
    }
  const Mesh dome = make_primitive("dome");
  const GridSpec d = GridSpec::covering(Vec2(-50, -50), Vec2(50, 50), 1.0);
  const std::vector<float> h = design_heights(dome, d, 0.0);
  double worst = 0;
  for (int j = 0; j < d.ny; ++j)
    for (int i = 0; i < d.nx; ++i) {
      const double r2 = d.cx(i) * d.cx(i) + d.cy(j) * d.cy(j);
      if (r2 > 30 * 30) continue;  // steeper, the facets' vertical gap grows as 1 / cos(slope)
      const double sphere = std::sqrt(2500 - r2);
      EXPECT_LE(h[d.index(i, j)], sphere + 1e-4);  // facets lie inside the sphere
      worst = std::max(worst, sphere - h[d.index(i, j)]);
    }
  // A facet spans 12 x 6 degrees: its vertices are within ~6.7 degrees of its centre; vertical gap / cos(37).
  EXPECT_LT(worst, 50 * (1 - std::cos(6.7 * M_PI / 180)) / 0.8);
}

TEST(VerifyDesign, CubeFacedAndContouredLeavesOnlyTheSquareCorners) {
  // 10 mm flat end: face the top at z 60 over the whole stock, then go round the cube at z 0 at a 5 mm offset
  // with sharp corners. Left: the stock's four corner squares beyond the tool's reach, 5x5 minus a quarter disc.
  std::string program = "G21 G90 G17\nT1 M6\n" + raster(-10, 70, -10, 70, 5, 60);
  program += "G0 Z80\nG0 X-5 Y-5\nG1 Z0\nG1 X65\nG1 Y65\nG1 X-5\nG1 Y-5\nG0 Z80\nM30\n";
  VerifyOptions o;
  o.resolution = 0.25;
  const VerifyResult r = verify_program(make_primitive("cube"), parse_gcode(program, "cube.ngc", tools("1=flat:10")),
                                        box(-10, -10, 0, 70, 70, 70), o);
  EXPECT_FALSE(r.report.gouged);
  EXPECT_EQ(r.report.max_gouge_mm, 0.0);
  EXPECT_NEAR(r.report.max_rest_mm, 60.0, 1e-4);
  const double left = 4 * (25 - 25 * M_PI / 4);
  const double area = cells_with_deviation_above(r.grid, 59) * o.resolution * o.resolution;
  EXPECT_NEAR(area, left, 1.5);
  EXPECT_NEAR(r.report.mean_rest_mm, 60 * area / (80 * 80), 1e-3);
  EXPECT_EQ(r.report.unreached_area_mm2, 0.0);
  EXPECT_EQ(r.report.cells, 320u * 320u);
  EXPECT_EQ(r.report.rapid_cut_cells, 0u);
}

TEST(VerifyDesign, CylinderRingCutByAFullCircle) {
  // A 10 mm flat end on a full circle of radius 30 at z 0 (G2 with I) around the 36-sided cylinder: the ring
  // 25..35 goes down to the floor. Never reached: the stock outside radius 35, and the slivers between the
  // polygon and the circle of radius 25 that the tool's round edge cannot enter.
  const std::string program = "G0 X30 Y0 Z70\nG1 Z0 F300\nG2 X30 Y0 I-30 J0\nG0 Z70\n";
  VerifyOptions o;
  o.resolution = 0.2;
  const VerifyResult r = verify_program(make_primitive("cylinder"), parse_gcode(program, "cyl.ngc", tools("flat:10")),
                                        box(-35, -35, 0, 35, 35, 60), o);
  EXPECT_FALSE(r.report.gouged);
  const double slivers = M_PI * 625 - 36 * 0.5 * 625 * std::sin(2 * M_PI / 36);
  const double outside = 70 * 70 - M_PI * 35 * 35;
  EXPECT_NEAR(r.report.unreached_area_mm2, outside + slivers, 6.0);
  EXPECT_NEAR(r.report.max_rest_mm, 60.0, 1e-4);
  // The ring itself is on the design.
  const GridSpec& g = r.grid.grid;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double rr = std::hypot(g.cx(i), g.cy(j));
      if (rr > 25.3 && rr < 34.7) { ASSERT_NEAR(r.grid.deviation[g.index(i, j)], 0.0, 1e-5) << rr; }
    }
}

TEST(VerifyDesign, DomeFinishedWithABallNeverCutsTheTrueSphere) {
  // A 6 mm ball follows the sphere offset by its radius (exact cutter locations for the true hemisphere) on a
  // raster at 1 mm stepover. The faceted dome lies inside the sphere, so: no gouge, and the material left is
  // the scallop (at most the flat-floor value on a convex surface) plus the facets' sagitta.
  const double R = 3, s = 1;
  std::ostringstream g;
  g << "G0 X-56 Y-56 Z60\n";
  for (int k = 0; k * s <= 112; ++k) {
    const double y = -56 + k * s;
    for (int q = 0; q <= 224; ++q) {
      const double x = k % 2 ? 56 - q * 0.5 : -56 + q * 0.5, rho2 = x * x + y * y;
      const double z = std::max(0.0, std::sqrt(std::max(0.0, (50 + R) * (50 + R) - rho2)) - R);
      g << "G1 X" << x << " Y" << y << " Z" << z << " F1000\n";
    }
  }
  VerifyOptions o;
  o.resolution = 0.25;
  o.compare.stepover = s;
  const VerifyResult r = verify_program(make_primitive("dome"), parse_gcode(g.str(), "dome.ngc", tools("ball:6")),
                                        box(-50, -50, 0, 50, 50, 52), o);
  const double flat_scallop = R - std::sqrt(R * R - 0.25 * s * s), sagitta = 50 * (1 - std::cos(M_PI / 30));
  EXPECT_FALSE(r.report.gouged) << r.report.max_gouge_mm;
  EXPECT_NEAR(r.report.scallop_theory_mm, flat_scallop, 1e-12);
  const GridSpec& grid = r.grid.grid;
  double worst_above = 0, worst_below = 0;
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const double rho2 = grid.cx(i) * grid.cx(i) + grid.cy(j) * grid.cy(j);
      if (rho2 > 20 * 20) continue;  // steeper, the horizontal stepover is wider along the surface
      const double d = r.grid.machined[grid.index(i, j)] - std::sqrt(2500 - rho2);
      worst_above = std::max(worst_above, d);
      worst_below = std::min(worst_below, d);
    }
  EXPECT_GT(worst_below, -1e-3);                // the true sphere is not cut (chords of 0.5 mm sag below it)
  EXPECT_LT(worst_above, flat_scallop + 0.005);  // convex and gentle: at most the flat-floor scallop
  EXPECT_GT(worst_above, 0.5 * flat_scallop);
  // Measured on the nearly flat top only: scallop plus the facets' sagitta.
  EXPECT_GT(r.report.scallop_mm, 0.5 * flat_scallop);
  EXPECT_LT(r.report.scallop_mm, flat_scallop + sagitta);
}

TEST(VerifyDesign, CloudOfTheCubeTopIsComparedWhereItHasPoints) {
  // The design as a scan: points every 0.5 mm over the cube's top (z 60). Faced exactly at 60 with a 10 mm flat
  // end, then one plunge to 59.3 at (30, 30): the gouge is 0.7 mm under the plunge, nothing is left, and only
  // the cells under the points (plus the few-cell gap filling at their border) are compared.
  PointCloud top;
  for (int j = 0; j <= 120; ++j)
    for (int i = 0; i <= 120; ++i) top.points.emplace_back(0.5 * i, 0.5 * j, 60.0);
  top.recompute_bbox();
  std::string program = "G21 G90 G17\nT1 M6\n" + raster(-10, 70, -10, 70, 5, 60) + "G0 Z80\nG0 X30 Y30\n";
  const uint32_t plunge = static_cast<uint32_t>(std::count(program.begin(), program.end(), '\n')) + 1;
  program += "G1 Z59.3\nG0 Z80\nM30\n";
  VerifyOptions o;
  o.resolution = 0.5;
  const VerifyResult r = verify_program(top, parse_gcode(program, "cloud.ngc", tools("1=flat:10")),
                                        box(-10, -10, 0, 70, 70, 62), o);
  ASSERT_TRUE(r.report.gouged);
  EXPECT_NEAR(r.report.max_gouge_mm, 0.7, 1e-4);
  EXPECT_LE(std::hypot(r.report.gouge_at.x() - 30, r.report.gouge_at.y() - 30), 5.0);
  EXPECT_NEAR(r.report.gouge_at.z(), 59.3, 1e-4);
  EXPECT_EQ(r.report.gouge_source, plunge);
  EXPECT_LT(r.report.max_rest_mm, 1e-4);
  EXPECT_EQ(r.report.cells, 160u * 160u);
  EXPECT_GE(r.report.compared_cells, 120u * 120u);
  EXPECT_LE(r.report.compared_cells, 128u * 128u);
}

TEST(VerifyDesign, MeshStockStartsAtItsTopSurface) {
  // The dome as both design and stock: before any cut nothing is left (a box stock leaves the corners' 50 mm).
  // A 6 mm ball along y = 0 at z 45 then gouges it by 5 mm at the pole, on that line.
  const Mesh dome = make_primitive("dome");
  StockSpec stock;
  stock.kind = StockSpec::Kind::Mesh;
  stock.mesh = &dome;
  VerifyOptions o;
  o.resolution = 0.5;
  const ToolSetup ball = tools("1=ball:6");
  const MachineProgram above = parse_gcode("T1 M6\nG0 X0 Y0 Z80\nM30\n", "above.ngc", ball);
  const VerifyResult untouched = verify_program(dome, above, stock, o);
  EXPECT_FALSE(untouched.report.gouged);
  EXPECT_LT(untouched.report.max_rest_mm, 1e-4);
  EXPECT_EQ(untouched.report.unreached_area_mm2, 0.0);
  EXPECT_NEAR(verify_program(dome, above, box(-50, -50, 0, 50, 50, 50), o).report.max_rest_mm, 50.0, 0.5);

  const MachineProgram cut = parse_gcode("T1 M6\nG0 X-60 Y0 Z80\nG1 Z45 F500\nG1 X60\nG0 Z80\nM30\n", "cut.ngc", ball);
  const VerifyResult r = verify_program(dome, cut, stock, o);
  ASSERT_TRUE(r.report.gouged);
  EXPECT_NEAR(r.report.max_gouge_mm, 5.0, 0.05);
  EXPECT_LE(std::hypot(r.report.gouge_at.x(), r.report.gouge_at.y()), 1.0);
  EXPECT_EQ(r.report.gouge_source, 4u);
  EXPECT_LT(r.report.max_rest_mm, 1e-4);
}
