// LevelMaterial's engagement (the adaptive planner's own measure): known answers for a straight side cut, a slot
// and air, against a count made here from the samples' definition, and the same counts on the AVX2 path and the
// scalar one. Its edge cells (where passes start) against their definition.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <utility>
#include <vector>

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

clip::Paths disc(const Vec2& c, double r) { return clip::offset(clip::rectangle(c, c + Vec2(0.01, 0.01)), r, 0.01); }

// Blobs over the map: discs, rectangles and a ring, so that arcs and edges meet at every angle, slivers and holes.
clip::Paths blobs(std::mt19937& rng) {
  std::uniform_real_distribution<double> at(2, 58), radius(0.3, 6);
  clip::Paths region;
  for (int k = 0; k < 30; ++k) region = clip::unite(region, disc(Vec2(at(rng), at(rng)), radius(rng)));
  for (int k = 0; k < 10; ++k) {
    const Vec2 a(at(rng), at(rng)), b(at(rng), at(rng));
    region = clip::unite(region, clip::rectangle(a.cwiseMin(b), a.cwiseMax(b)));
  }
  return clip::unite(region, clip::subtract(disc(Vec2(20, 20), 9), disc(Vec2(20, 20), 8)));  // a ring
}

TEST(LevelMaterial, EngagementCountsTheSamplesOnBothPaths) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> at(2, 58), unit(-1, 1);
  LevelMaterial m = map_of(blobs(rng));
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

// Every block's edge cells, in order, against their definition checked cell by cell here: material cells with air
// among their eight neighbours on the map, not skipped; each with the unit sum of the directions to the air within
// two cells, weighted by inverse distance. The map runs to the grid's edges (blocks read unchecked inside, checked
// along the edges) and holds the part's cells too (neither air nor material).
TEST(LevelMaterial, EdgeCellsAreTheMaterialCellsBesideAir) {
  std::mt19937 rng(30);
  LevelMaterial m;
  m.reset(Vec2(0, 0), Vec2(60.1, 59.9), kCell);  // 481 x 480 cells: the last column of blocks one cell wide
  m.fill(clip::rectangle(Vec2(-1, -1), Vec2(61, 61)), LevelMaterial::kAir);
  m.fill(blobs(rng), LevelMaterial::kMaterial);
  m.fill(clip::unite(disc(Vec2(40, 40), 7), clip::rectangle(Vec2(56, -1), Vec2(61, 61))), LevelMaterial::kOther);
  const long nx = m.nx(), ny = m.ny();
  const auto is = [&](long i, long j, uint8_t v) {
    return i >= 0 && j >= 0 && i < nx && j < ny && m.value(size_t(j) * nx + i) == v;
  };
  const auto skip = [](size_t c) { return c % 7 == 3; };
  size_t found = 0;
  for (long bj = 0; bj < m.blocks_y(); ++bj)
    for (long bi = 0; bi < m.blocks_x(); ++bi) {
      std::vector<std::pair<size_t, Vec2>> got, expected;
      m.edge_cells(bi, bj, skip, [&](size_t c, const Vec2&, const Vec2& n) { got.push_back({c, n}); });
      for (long j = bj * 16; j < std::min(ny, (bj + 1) * 16); ++j)
        for (long i = bi * 16; i < std::min(nx, (bi + 1) * 16); ++i) {
          const size_t c = size_t(j) * nx + i;
          bool beside_air = false;
          for (long dj = -1; dj <= 1; ++dj)
            for (long di = -1; di <= 1; ++di) beside_air = beside_air || is(i + di, j + dj, LevelMaterial::kAir);
          if (!is(i, j, LevelMaterial::kMaterial) || !beside_air || skip(c)) continue;
          Vec2 g = Vec2::Zero();
          for (long dj = -2; dj <= 2; ++dj)
            for (long di = -2; di <= 2; ++di)
              if ((di || dj) && is(i + di, j + dj, LevelMaterial::kAir)) g += Vec2(di, dj) / std::hypot(di, dj);
          if (g.norm() > 1e-9) expected.push_back({c, g.normalized()});
        }
      ASSERT_EQ(got.size(), expected.size()) << "block " << bi << ", " << bj;
      for (size_t k = 0; k < got.size(); ++k) {
        ASSERT_EQ(got[k].first, expected[k].first) << "block " << bi << ", " << bj;
        EXPECT_NEAR((got[k].second - expected[k].second).norm(), 0.0, 1e-12);
      }
      found += got.size();
    }
  EXPECT_GT(found, 1000u);  // the blobs' edges, not an empty map
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
