// LevelMaterial's engagement (the adaptive planner's own measure): known answers for a straight side cut, a slot
// and air, against a count made here from the samples' definition, and the same counts on the AVX2 path and the
// scalar one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "rosmill/geometry/clip_region.hpp"
#include "rosmill/plan/level_material.hpp"

using namespace rosmill::core;

namespace {

constexpr double kCell = 0.125;

// A 60 x 60 mm map, air everywhere, then `region` material.
LevelMaterial map_of(const clip::Paths& region) {
  LevelMaterial m;
  m.reset(Vec2(0, 0), Vec2(60, 60), kCell);
  m.fill(clip::rectangle(Vec2(0, 0), Vec2(60, 60)), LevelMaterial::kAir);
  m.fill(region, LevelMaterial::kMaterial);
  return m;
}

// The definition, counted here: 90 samples of the half-circle ahead of dir, at -90 + (k + 0.5) * 2 degrees from
// it, each in material when the cell it falls in is; 2 degrees each.
double engagement_by_definition(const LevelMaterial& m, const Vec2& p, const Vec2& dir, double r) {
  const double heading = std::atan2(dir.y(), dir.x());
  int in = 0;
  for (int k = 0; k < 90; ++k) {
    const double a = heading + (-90 + (k + 0.5) * 2) * M_PI / 180;
    in += m.material(p + r * Vec2(std::cos(a), std::sin(a)));
  }
  return 2.0 * in;
}

TEST(LevelMaterial, SideCutSlotAndAirHaveTheirEngagement) {
  // Material right of x = 30 (to the grid's edge); the cutter moves +y with the material on its right.
  const LevelMaterial m = map_of(clip::rectangle(Vec2(30, 0), Vec2(60, 60)));
  const double R = 2.5;
  for (double ae : {0.1, 0.5, 1.0, 1.25, 2.5, 4.0}) {
    const Vec2 p(30 - R + ae, 30);  // the disc reaches ae into the material
    const double expected = std::acos(1 - ae / R) * 180 / M_PI;  // the side cut's own angle
    // Within a sample and the half cell by which the map's edge stands from the true one.
    const double slack = 2 + std::acos(1 - std::min(2.0, (ae + 0.5 * kCell) / R)) * 180 / M_PI -
                         std::acos(1 - std::min(2.0, ae / R)) * 180 / M_PI;
    EXPECT_NEAR(m.engagement(p, Vec2(0, 1), R), expected, slack) << "ae " << ae;
  }
  EXPECT_DOUBLE_EQ(m.engagement(Vec2(45, 30), Vec2(0, 1), R), 180.0);  // a slot: all material
  EXPECT_DOUBLE_EQ(m.engagement(Vec2(10, 30), Vec2(0, 1), R), 0.0);    // air
  EXPECT_DOUBLE_EQ(m.engagement(Vec2(30 - R - 0.2, 30), Vec2(0, 1), R), 0.0);  // beside the material, not in it
}

TEST(LevelMaterial, EngagementCountsTheSamplesOnBothPaths) {
  // Blobs of material: discs and an annulus, so that arcs meet edges at every angle, slivers and holes.
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> at(2, 58), radius(0.3, 6), unit(-1, 1);
  const auto disc = [](const Vec2& c, double r) {
    return clip::offset(clip::rectangle(c, c + Vec2(0.01, 0.01)), r, 0.01);
  };
  clip::Paths region;
  for (int k = 0; k < 30; ++k) region = clip::unite(region, disc(Vec2(at(rng), at(rng)), radius(rng)));
  for (int k = 0; k < 10; ++k) {
    const Vec2 a(at(rng), at(rng)), b(at(rng), at(rng));
    region = clip::unite(region, clip::rectangle(a.cwiseMin(b), a.cwiseMax(b)));
  }
  region = clip::unite(region, clip::subtract(disc(Vec2(20, 20), 9), disc(Vec2(20, 20), 8)));  // a ring
  LevelMaterial m = map_of(region);
  const bool vector = LevelMaterial::vector_arcs();
  int checked = 0, defined_apart = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec2 p(at(rng), at(rng));
    Vec2 dir(unit(rng), unit(rng));
    if (dir.norm() < 1e-3) continue;
    dir.normalize();
    const double r = 0.5 + 4 * (unit(rng) + 1) / 2;
    LevelMaterial::use_vector_arcs(vector);
    const double e = m.engagement(p, dir, r);
    // The count from the definition: the same samples, placed by other arithmetic (cos and sin of the sum of
    // angles): a sample within rounding of a cell's edge may fall in its neighbour.
    const double by_definition = engagement_by_definition(m, p, dir, r);
    EXPECT_NEAR(e, by_definition, 4.0) << "at " << p.transpose() << " dir " << dir.transpose() << " r " << r;
    defined_apart += e != by_definition;
    for (double deg : {0.0, 1.0, 30.0, 63.0, 88.0, 179.0})
      ASSERT_EQ(m.engaged_over(p, dir, r, deg), e > deg) << deg;
    // The scalar path gives the same count and the same decisions, bit for bit.
    LevelMaterial::use_vector_arcs(false);
    ASSERT_EQ(m.engagement(p, dir, r), e) << "at " << p.transpose() << " dir " << dir.transpose() << " r " << r;
    for (double deg : {0.0, 1.0, 30.0, 63.0, 88.0, 179.0}) ASSERT_EQ(m.engaged_over(p, dir, r, deg), e > deg);
    ++checked;
  }
  LevelMaterial::use_vector_arcs(vector);
  EXPECT_GT(checked, 19000);
  EXPECT_LT(defined_apart, checked / 100);  // rounding, not a different measure
  std::printf("vector path on this machine: %s; %d of %d counts a sample apart from the definition's\n",
              vector ? "yes" : "no", defined_apart, checked);
}

TEST(LevelMaterial, ArcsOffTheGridCountOnlyWhatLiesOnIt) {
  // Material everywhere on the map: a half-circle that reaches past the map's edge counts its samples on it.
  const LevelMaterial m = map_of(clip::rectangle(Vec2(0, 0), Vec2(60, 60)));
  const double R = 2.5;
  EXPECT_DOUBLE_EQ(m.engagement(Vec2(30, 30), Vec2(1, 0), R), 180.0);
  // Centre on the left edge heading +y: the half-circle's right half (toward +x) is on the map.
  const double e = m.engagement(Vec2(0, 30), Vec2(0, 1), R);
  EXPECT_NEAR(e, 90.0, 2.0);
  EXPECT_DOUBLE_EQ(e, engagement_by_definition(m, Vec2(0, 30), Vec2(0, 1), R));
  EXPECT_DOUBLE_EQ(m.engagement(Vec2(-10, 30), Vec2(0, 1), R), 0.0);  // off the map altogether
}

}  // namespace
