// The deviation map's colour bands, the points the ROS layer publishes, and the picture.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "rosmill/error.hpp"
#include "rosmill/geometry/outline_from_above.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/testing/png_pixels.hpp"
#include "rosmill/verify/deviation_image.hpp"
#include "rosmill/verify/deviation_map.hpp"
#include "rosmill/verify/gcode_reader.hpp"
#include "rosmill/verify/inspection_image.hpp"
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

namespace {

// Pixels of a picture that are exactly `c`, and those dark enough to be text or lines, in a rectangle.
size_t count_colour(const picture::Canvas& img, Rgb c, int x0 = 0, int y0 = 0, int x1 = 1 << 20, int y1 = 1 << 20) {
  size_t n = 0;
  for (int y = y0; y < std::min(y1, img.height()); ++y)
    for (int x = x0; x < std::min(x1, img.width()); ++x) {
      const Rgb p = img.pixel(x, y);
      n += p.r == c.r && p.g == c.g && p.b == c.b;
    }
  return n;
}
size_t dark_pixels(const picture::Canvas& img, int x0, int y0, int x1, int y1) {
  size_t n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const Rgb p = img.pixel(x, y);
      n += p.r < 110 && p.g < 110 && p.b < 110;
    }
  return n;
}
bool same(Rgb a, Rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

// A scan of a 40 x 30 mm floor every 0.5 mm, on the design but for a deficit of 0.5 mm about (30, 10) and an
// excess of 0.2 mm about (8, 22).
scan::InspectionReport floor_scan() {
  scan::InspectionReport r;
  for (int j = 0; j <= 60; ++j)
    for (int i = 0; i <= 80; ++i) {
      const Vec3 p(0.5 * i, 0.5 * j, 0);
      const double d = (p - Vec3(30, 10, 0)).norm() < 3 ? -0.5 : (p - Vec3(8, 22, 0)).norm() < 2 ? 0.2 : 0.0;
      r.points.push_back(p);
      r.deviations.push_back(d);
      r.within_tolerance += d == 0;
    }
  r.largest_deficit = {-0.5, Vec3(30, 10, 0)};
  r.largest_excess = {0.2, Vec3(8, 22, 0)};
  return r;
}

const picture::MapCaption kCaption{"deviation map", "cube.stl", "program g.ngc", "2024-05-17"};

}  // namespace

TEST(VerifyMap, PictureShowsTheMapUpAndTheLegend) {
  const VerifyResult r = gouged_cube();
  const picture::MapPicture pic = deviation_picture(r.grid, r.report, outline_from_above(make_primitive("cube")), kCaption);
  const picture::Canvas& img = pic.canvas;
  const picture::MapFrame& f = pic.frame;
  // The 60 mm square at 800 pixels, +y up: the gouge at (30.1, 20.1) is in the lower half of the map.
  EXPECT_NEAR(f.scale, 800 / 60.0, 1e-9);
  EXPECT_EQ(f.width, 800);
  EXPECT_GT(f.pixel(30.1, 20.1).y(), f.top + f.height / 2);
  const Vec2 edge = f.pixel(30.1 + 1.25, 20.1);  // 1.25 mm from the centre: inside the 2.6 mm cap, past the ring
  const Rgb at_crater_edge = img.pixel(int(edge.x()), int(edge.y()));
  EXPECT_TRUE(at_crater_edge.r > 150 && at_crater_edge.g < 100) << int(at_crater_edge.r) << "," << int(at_crater_edge.g);
  const std::vector<DeviationBand> bands = deviation_bands(0.01);
  const Vec2 far = f.pixel(10, 50);
  EXPECT_TRUE(same(img.pixel(int(far.x()), int(far.y())), bands[4].colour));  // on the design far from the gouge
  // The colour bar: every band's swatch (30 x 22 pixels).
  for (const DeviationBand& b : bands) EXPECT_GE(count_colour(img, b.colour), 28u * 20) << b.label;
  // Text: the title over the map, the x numbers under it, the y numbers left of it, the legend beside it.
  EXPECT_GT(dark_pixels(img, 0, 0, img.width(), int(f.top) - 4), 300u);
  EXPECT_GT(dark_pixels(img, int(f.left), int(f.top) + f.height + 8, int(f.left) + f.width, img.height()), 200u);
  EXPECT_GT(dark_pixels(img, 0, int(f.top), int(f.left) - 8, int(f.top) + f.height), 200u);
  EXPECT_GT(img.width(), int(f.left) + f.width + 300);
  // The outline: the cube's edge is the map's border, drawn dark over the cells' green.
  const Vec2 side = f.pixel(0, 30);
  EXPECT_LT(img.pixel(int(side.x()), int(side.y())).g, 110);
}

TEST(VerifyMap, PngIsWrittenAndReadsBackTheSame) {
  const VerifyResult r = gouged_cube();
  const picture::MapPicture pic = deviation_picture(r.grid, r.report, {}, kCaption);
  const std::string path = ::testing::TempDir() + "rosmill_deviation_map.png";
  std::remove(path.c_str());
  write_deviation_png(path, r.grid, r.report, {}, kCaption);
  const rosmill::testing::PngPixels png = rosmill::testing::read_png_pixels(path);
  ASSERT_EQ(png.width, pic.canvas.width());
  ASSERT_EQ(png.height, pic.canvas.height());
  const Vec2 far = pic.frame.pixel(10, 50);
  EXPECT_TRUE(same(png.at(int(far.x()), int(far.y())), deviation_bands(0.01)[4].colour));
  // A folder that does not exist: the error names the file.
  const std::string bad = ::testing::TempDir() + "no_such_folder/map.png";
  try {
    write_deviation_png(bad, r.grid, r.report, {}, kCaption);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
}

TEST(VerifyMap, InspectionPictureDrawsPointsAtTheirSizeInTheirBands) {
  Contour square;
  square.points = {Vec2(0, 0), Vec2(40, 0), Vec2(40, 30), Vec2(0, 30)};
  const picture::MapCaption caption{"inspection map", "floor.stl", "scan floor.pcd", "2024-05-17"};
  const picture::MapPicture pic = inspection_picture(floor_scan(), 0.05, {square}, caption);
  const picture::Canvas& img = pic.canvas;
  const picture::MapFrame& f = pic.frame;
  const std::vector<DeviationBand> bands = deviation_bands(0.05);
  auto at = [&](double x, double y) {
    const Vec2 p = f.pixel(x, y);
    return img.pixel(int(p.x()), int(p.y()));
  };
  EXPECT_TRUE(same(at(30.1, 10), bands[2].colour));  // deficit 0.5 - 5 mm
  EXPECT_TRUE(same(at(8.1, 22), bands[5].colour));   // excess 0.05 - 0.5 mm
  EXPECT_TRUE(same(at(20.1, 15), bands[4].colour));  // on the design
  // Discs 0.5 mm across (the spacing), about 10 pixels: a pixel 0.15 mm from a point is still its colour.
  EXPECT_GT(0.5 * f.scale, 8.0);
  EXPECT_TRUE(same(at(20.15, 15.05), bands[4].colour));
  // The outline's corner, the title and the colour bar of the nine bands a scan can have.
  EXPECT_LT(at(40, 15).g, 110);
  EXPECT_GT(dark_pixels(img, 0, 0, img.width(), int(f.top) - 4), 300u);
  for (size_t b = 0; b < 9; ++b) EXPECT_GE(count_colour(img, bands[b].colour), 28u * 20) << bands[b].label;
  EXPECT_EQ(count_colour(img, bands[10].colour, int(f.left), int(f.top), int(f.left) + f.width, int(f.top) + f.height), 0u);
  // An unwritable path names itself.
  const std::string bad = ::testing::TempDir() + "no_such_folder/inspection.png";
  EXPECT_THROW(write_inspection_png(bad, floor_scan(), 0.05, {square}, caption), Error);
}
