// Dubins paths (geometry/dubins.hpp): known answers and the properties every word must have, checked by sampling
// the path it describes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <string>

#include "rosmill/geometry/dubins.hpp"

using namespace rosmill::core;

namespace {

Vec2 heading(double a) { return {std::cos(a), std::sin(a)}; }

// The largest turn per unit length between consecutive chords of the sampled path (its curvature, from the
// points only).
double sampled_curvature(const Vec2& from, const std::vector<Vec2>& pts) {
  double worst = 0;
  Vec2 prev = from;
  for (size_t k = 0; k + 1 < pts.size(); ++k) {
    const Vec2 u = pts[k] - prev, v = pts[k + 1] - pts[k];
    const double turn = std::abs(std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v)));
    worst = std::max(worst, turn / std::min(u.norm(), v.norm()));
    prev = pts[k];
  }
  return worst;
}

}  // namespace

TEST(Dubins, AlignedPosesAreJoinedByTheStraightLine) {
  const std::vector<DubinsPath> paths = dubins_paths({0, 0}, {1, 0}, {10, 0}, {1, 0}, 1.0);
  ASSERT_FALSE(paths.empty());
  EXPECT_NEAR(paths.front().length(), 10.0, 1e-9);
}

TEST(Dubins, TurningBackNeedsAHalfCircle) {
  // From the origin heading +x to (0, 2) heading -x with radius 1: a left half circle, length pi.
  const std::vector<DubinsPath> paths = dubins_paths({0, 0}, {1, 0}, {0, 2}, {-1, 0}, 1.0);
  ASSERT_FALSE(paths.empty());
  EXPECT_NEAR(paths.front().length(), M_PI, 1e-9);
}

TEST(Dubins, EveryWordEndsAtTheGoalAndTurnsNoSharperThanItsRadius) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-5, 5), ang(-M_PI, M_PI);
  std::set<std::string> words;  // every word's closed form is exercised
  for (int trial = 0; trial < 200; ++trial) {
    const Vec2 a(pos(rng), pos(rng)), b(pos(rng), pos(rng));
    const Vec2 ha = heading(ang(rng)), hb = heading(ang(rng));
    const double rho = 0.5 + 0.01 * trial;
    const std::vector<DubinsPath> paths = dubins_paths(a, ha, b, hb, rho);
    ASSERT_FALSE(paths.empty()) << "trial " << trial;  // LSL or RSR always exists
    for (size_t k = 1; k < paths.size(); ++k) EXPECT_LE(paths[k - 1].length(), paths[k].length());
    // No path is shorter than the straight distance.
    EXPECT_GE(paths.front().length(), (b - a).norm() - 1e-9);
    for (const DubinsPath& p : paths) {
      words.insert(std::string(p.word, 3));
      const std::vector<Vec2> pts = dubins_points(p, a, ha, 0.01);
      ASSERT_FALSE(pts.empty());
      EXPECT_LT((pts.back() - b).norm(), 1e-6);
      EXPECT_LE(sampled_curvature(a, pts), 1 / rho * 1.001 + 1e-9) << p.word[0] << p.word[1] << p.word[2];
    }
  }
  EXPECT_EQ(words, std::set<std::string>({"LSL", "RSR", "LSR", "RSL", "RLR", "LRL"}));
}
