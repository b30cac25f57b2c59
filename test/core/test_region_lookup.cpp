// RegionLookup against clip::contains (Clipper's own point-in-polygon test, which it must agree with): random
// points over regions with holes, curved boundaries and vertices on its grid's cell centres, and points exactly on
// the boundary (inside, as clip::contains counts them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/geometry/clip_region.hpp"
#include "rosmill/geometry/region_lookup.hpp"
#include "rosmill/testing/sanitized.hpp"

using namespace rosmill::core;

namespace {

// Disagreements with clip::contains over n random points in the region's box grown by `margin`.
size_t disagreements(const clip::Paths& region, double cell, size_t n, double margin, unsigned seed) {
  const RegionLookup lookup(region, cell);
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
  for (const clip::Path& path : region)
    for (const auto& q : path) lo = lo.cwiseMin(clip::from_point(q)), hi = hi.cwiseMax(clip::from_point(q));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(lo.x() - margin, hi.x() + margin), y(lo.y() - margin, hi.y() + margin);
  size_t wrong = 0;
  for (size_t k = 0; k < n; ++k) {
    const Vec2 p(x(rng), y(rng));
    wrong += lookup.contains(p) != clip::contains(region, p);
  }
  return wrong;
}

// A 60 x 40 block less a round pocket and a square hole, grown and shrunk: round arcs, holes, a narrow neck.
clip::Paths pocketed_block() {
  clip::Paths block = clip::rectangle(Vec2(0, 0), Vec2(60, 40));
  block = clip::subtract(block, clip::sweep({{Vec2(20, 20)}}, 8, 0.01));
  block = clip::subtract(block, clip::rectangle(Vec2(40, 10), Vec2(50, 30)));
  return clip::offset(clip::offset(block, -1.5, 0.01), 0.7, 0.01);
}

}  // namespace

TEST(RegionLookup, AgreesWithClipperEverywhere) {
  const size_t n = size_t(rosmill::testing::cases(200000, 20000));
  const clip::Paths region = pocketed_block();
  for (double cell : {0.05, 0.5, 2.0, 25.0}) {
    SCOPED_TRACE(cell);
    EXPECT_EQ(disagreements(region, cell, n, 3.0, 7), 0u);
  }
  // A ring (the groove of bench/adaptive_vs_freecad: a 30-gon annulus), and two islands apart.
  clip::Paths ring = clip::subtract(clip::sweep({{Vec2(0, 0)}}, 57.5, 0.05), clip::sweep({{Vec2(0, 0)}}, 52.5, 0.05));
  EXPECT_EQ(disagreements(ring, 0.5, n, 2.0, 11), 0u);
  clip::Paths islands = clip::unite(clip::rectangle(Vec2(0, 0), Vec2(1, 1)), clip::rectangle(Vec2(5, 5), Vec2(7, 6)));
  EXPECT_EQ(disagreements(islands, 0.3, n, 1.0, 13), 0u);
}

TEST(RegionLookup, BoundaryAndVerticesOnCellCentresCountAsInside) {
  // The grid starts a cell below the region's box: cells of 1 from (-1, -1), centres at -0.5, 0.5, ... The
  // square's right and top edges run through cell centres.
  const clip::Paths square = clip::rectangle(Vec2(0, 0), Vec2(10.5, 10.5));
  const RegionLookup lookup(square, 1.0);
  for (double t = 0; t <= 10.5; t += 0.125) {
    EXPECT_TRUE(lookup.contains(Vec2(t, 0)));
    EXPECT_TRUE(lookup.contains(Vec2(10.5, t)));
    EXPECT_TRUE(lookup.contains(Vec2(t, 10.5)));
    EXPECT_TRUE(lookup.contains(Vec2(0, t)));
    EXPECT_FALSE(lookup.contains(Vec2(t, -1e-3)));
    EXPECT_FALSE(lookup.contains(Vec2(10.5 + 1e-3, t)));
    EXPECT_FALSE(lookup.contains(Vec2(t, 10.5 + 1e-3)));
    EXPECT_TRUE(lookup.contains(Vec2(std::min(t, 10.4), 10.5 - 1e-3)));
  }
  EXPECT_EQ(disagreements(square, 1.0, 100000, 2.0, 17), 0u);
  // A diamond with a vertex on a cell centre (10.5, 5.5): a point level with it crosses one edge or none there.
  const clip::Paths diamond = {clip::to_path({Vec2(5.5, 0), Vec2(10.5, 5.5), Vec2(5.5, 11), Vec2(0, 5.5)})};
  const RegionLookup d(diamond, 1.0);
  EXPECT_TRUE(d.contains(Vec2(5.5, 5.5)));
  EXPECT_TRUE(d.contains(Vec2(10.5, 5.5)));
  EXPECT_FALSE(d.contains(Vec2(10.6, 5.5)));
  EXPECT_TRUE(d.contains(Vec2(10.4, 5.5)));
  EXPECT_FALSE(d.contains(Vec2(10.5, 5.4)));
  EXPECT_EQ(disagreements(diamond, 1.0, 100000, 2.0, 19), 0u);
}

TEST(RegionLookup, EmptyRegionHoldsNothingAndAGridTooLargeIsRefused) {
  const RegionLookup none(clip::Paths{}, 1.0);
  EXPECT_FALSE(none.contains(Vec2(0, 0)));
  EXPECT_FALSE(RegionLookup(pocketed_block(), 1.0).contains(Vec2(NAN, 5)));
  // A kilometre square at 0.01 mm: refused before anything is allocated, saying the grid's size.
  try {
    RegionLookup(clip::rectangle(Vec2(0, 0), Vec2(1e6, 1e6)), 0.01);
    FAIL() << "no error";
  } catch (const rosmill::core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("too large"), std::string::npos) << e.what();
  }
}
