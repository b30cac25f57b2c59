// The picture area: nice axis steps, the canvas's errors, and the outline of a mesh seen from above.
#include <gtest/gtest.h>

#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/geometry/outline_from_above.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/picture/canvas.hpp"
#include "rosmill/picture/map_plot.hpp"
#include "rosmill/picture/nice_ticks.hpp"

using namespace rosmill::core;
using namespace rosmill::core::picture;

TEST(Picture, AxisStepsAreOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(nice_step(60, 10), 10);   // 6 a tick -> 10
  EXPECT_DOUBLE_EQ(nice_step(7, 5), 2);      // 1.4 -> 2
  EXPECT_DOUBLE_EQ(nice_step(0.37, 4), 0.1);  // 0.0925 -> 0.1
  EXPECT_DOUBLE_EQ(nice_step(50, 10), 5);    // exactly 5
  EXPECT_DOUBLE_EQ(nice_step(2.9, 1), 5);
  EXPECT_EQ(ticks(-3, 7, 2), (std::vector<double>{-2, 0, 2, 4, 6}));
  EXPECT_EQ(ticks(0, 60, 10).size(), 7u);
  EXPECT_EQ(tick_label(-1e-12, 0.5), "0.0");  // no "-0.0"; every label of an axis with as many decimals
  EXPECT_EQ(tick_label(2.5, 0.5), "2.5");
  EXPECT_EQ(tick_label(20, 10), "20");
  EXPECT_EQ(tick_label(0.3, 0.1), "0.3");
  EXPECT_THROW(nice_step(0, 5), Error);
  EXPECT_THROW(nice_step(NAN, 5), Error);
}

TEST(Picture, BadSizesAndRegionsAreRefusedWithTheirName) {
  try {
    Canvas(0, 10, "test picture");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "test picture");
  }
  EXPECT_THROW(Canvas(40000, 10, "test picture"), Error);
  EXPECT_THROW(MapPlot(0, 0, 0, 10, MapCaption{}, MapLegend{}, "test map"), Error);
  EXPECT_THROW(MapPlot(0, 0, NAN, 10, MapCaption{}, MapLegend{}, "test map"), Error);
  const Canvas c(20, 10, "test picture");
  EXPECT_EQ(c.pixel(19, 9).r, 255);  // white
  EXPECT_THROW(c.pixel(20, 0), Error);
}

TEST(Picture, TitleNamesTheMapThePartTheSourceAndTheDate) {
  EXPECT_EQ((MapCaption{"deviation map", "cube.stl", "program g.ngc", "2024-05-17"}.title()),
            "deviation map of cube.stl, program g.ngc, 2024-05-17");
  const std::string today = local_iso_date();
  ASSERT_EQ(today.size(), 10u);
  EXPECT_EQ(today[4], '-');
  EXPECT_EQ(today[7], '-');
  EXPECT_EQ((MapCaption{"inspection map", "", "", ""}.title()), "inspection map, " + today);
}

TEST(Picture, OutlineFromAboveIsTheSilhouette) {
  const std::vector<Contour> cube = outline_from_above(make_primitive("cube"));  // [0, 60]^3
  ASSERT_EQ(cube.size(), 1u);
  EXPECT_FALSE(cube[0].hole);
  EXPECT_NEAR(cube[0].area, 3600, 1e-6);
  // The dome (a hemisphere of radius 50 in 900 facets): a disc a little smaller than pi r^2.
  const std::vector<Contour> dome = outline_from_above(make_primitive("dome"));
  ASSERT_EQ(dome.size(), 1u);
  EXPECT_LT(dome[0].area, M_PI * 2500);
  EXPECT_GT(dome[0].area, 0.98 * M_PI * 2500);
}
