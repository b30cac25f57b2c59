// The deviation map's colour bands, the points the ROS layer publishes, and the picture.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rosmill/geometry/primitives.hpp"
#include "rosmill/verify/deviation_image.hpp"
#include "rosmill/verify/deviation_map.hpp"
#include "rosmill/verify/gcode_reader.hpp"
#include "test_verify_programs.hpp"

using namespace verify_test;

namespace {

VerifyResult gouged_cube() {
  const std::string program =
      facing() + "T2 M6\nG0 X30.1 Y20.1 Z62\nG1 Z61 F300\nG1 Z58.5\nG0 Z70\nG0 X70 Y70\nM30\n";
  VerifyOptions o;
  o.resolution = 0.25;
  return verify_program(make_primitive("cube"), parse_gcode(program, "g.ngc", tool_setup({"1=flat:10", "2=ball:6"})),
                        box(0, 0, 0, 60, 60, 65), o);
}

}  // namespace

TEST(VerifyMap, BandsAreDecadesOfTheTolerance) {
  const double tol = 0.01;
  const std::vector<DeviationBand> bands = deviation_bands(tol);
  ASSERT_EQ(bands.size(), 11u);
  EXPECT_EQ(bands[deviation_band(-50, true, tol)].label, "gouge > 10");
  EXPECT_EQ(bands[deviation_band(-1.5, true, tol)].label, "gouge 1 - 10");
  EXPECT_EQ(bands[deviation_band(-0.05, true, tol)].label, "gouge 0.01 - 0.1");
  EXPECT_EQ(bands[deviation_band(-0.005, true, tol)].label, "on design +/- 0.01");
  EXPECT_EQ(bands[deviation_band(0.009, false, tol)].label, "on design +/- 0.01");
  EXPECT_EQ(bands[deviation_band(0.05, true, tol)].label, "rest 0.01 - 0.1");
  EXPECT_EQ(bands[deviation_band(0.5, true, tol)].label, "rest 0.1 - 1");
  EXPECT_EQ(bands[deviation_band(20, true, tol)].label, "rest > 10");
  EXPECT_EQ(bands[deviation_band(20, false, tol)].label, "not cut");
  EXPECT_EQ(bands[deviation_band(std::numeric_limits<double>::quiet_NaN(), true, tol)].label, "no design");
}

TEST(VerifyMap, PointsForTheRosCloudKeepTheGouge) {
  const VerifyResult r = gouged_cube();
  const DeviationGrid& g = r.grid;
  const std::vector<DeviationPoint> all = deviation_points(g);
  ASSERT_EQ(all.size(), g.grid.cells());  // a mesh design is known everywhere
  const std::vector<DeviationBand> bands = deviation_bands(0.01);
  size_t gouged = 0;
  for (const DeviationPoint& p : all) {
    EXPECT_NEAR(p.position.z() - p.deviation, 60.0, 1e-4);  // machined - deviation = the design (the top)
    const Rgb want = bands[deviation_band(p.deviation, true, 0.01)].colour;
    ASSERT_TRUE(p.colour.r == want.r && p.colour.g == want.g && p.colour.b == want.b);
    if (p.deviation >= -0.01) continue;
    ++gouged;
    EXPECT_GT(p.colour.r, p.colour.g);  // reds for gouges
  }
  EXPECT_EQ(gouged, r.report.gouge_cells);
  // Thinned to 1000 points, the deepest cell of each block stays: the gouge is still there, as deep.
  const std::vector<DeviationPoint> few = deviation_points(g, 1000);
  EXPECT_LE(few.size(), 1000u);
  EXPECT_GT(few.size(), 500u);
  double deepest = 0;
  for (const DeviationPoint& p : few) deepest = std::min<double>(deepest, p.deviation);
  EXPECT_NEAR(-deepest, r.report.max_gouge_mm, 1e-6);
}

TEST(VerifyMap, PictureShowsTheMapUpAndTheLegend) {
  const VerifyResult r = gouged_cube();
  const RgbImage img = deviation_image(r.grid, r.report);
  // 240 x 240 cells drawn 3 pixels a cell, +y up: the gouge at (30.1, 20.1) is in the lower half of the map.
  const int margin = 16, zoom = 3, h = 240 * zoom;
  const int px = margin + static_cast<int>(30.1 / 0.25) * zoom + 1, py = margin + h - static_cast<int>(20.1 / 0.25) * zoom - 1;
  const std::vector<DeviationBand> bands = deviation_bands(0.01);
  const Rgb at_crater_edge = img.at(px + 5 * zoom, py);  // 1.25 mm from the centre: inside the 2.6 mm cap
  EXPECT_TRUE(at_crater_edge.r > 150 && at_crater_edge.g < 100) << int(at_crater_edge.r) << "," << int(at_crater_edge.g);
  const Rgb top = img.at(margin + 10, margin + 10);
  EXPECT_EQ(top.g, bands[4].colour.g);  // on the design far from the gouge
  EXPECT_GT(img.width, margin + 240 * zoom + 400);
}
