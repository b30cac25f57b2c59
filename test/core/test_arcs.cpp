// Arc fitting: fewer blocks, and the fitted program stays within the tolerance of the polyline (checked by
// sampling both the arcs and the polyline).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rosmill/gcode/arc_fit.hpp"
#include "rosmill/gcode/post.hpp"
#include "test_post_jobs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::gcode;

namespace {

std::vector<Vec3> circle(double cx, double cy, double r, double a0, double a1, int n, double z = 0) {
  std::vector<Vec3> pts;
  for (int i = 0; i <= n; ++i) {
    const double a = a0 + (a1 - a0) * i / n;
    pts.emplace_back(cx + r * std::cos(a), cy + r * std::sin(a), z);
  }
  return pts;
}

double dist_point_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

double dist_to_polyline(const Vec2& p, const std::vector<Vec3>& pts, int first, int last) {
  double d = INFINITY;
  for (int i = first; i < last; ++i) d = std::min(d, dist_point_segment(p, pts[i].head<2>(), pts[i + 1].head<2>()));
  return d;
}

// Two-sided check by sampling: points on each arc near the polyline, and points on the polyline near the arc.
double max_deviation(const std::vector<Vec3>& pts, const std::vector<ArcPiece>& pieces) {
  double worst = 0;
  for (const ArcPiece& a : pieces) {
    if (!a.arc) continue;
    const Vec2 from = pts[a.first].head<2>(), to = pts[a.last].head<2>();
    double a0 = std::atan2(from.y() - a.centre.y(), from.x() - a.centre.x());
    double a1 = std::atan2(to.y() - a.centre.y(), to.x() - a.centre.x());
    if (a.clockwise && a1 > a0) a1 -= 2 * M_PI;
    if (!a.clockwise && a1 < a0) a1 += 2 * M_PI;
    for (int s = 0; s <= 400; ++s) {
      const double ang = a0 + (a1 - a0) * s / 400;
      const Vec2 p = a.centre + a.radius * Vec2(std::cos(ang), std::sin(ang));
      worst = std::max(worst, dist_to_polyline(p, pts, a.first, a.last));
    }
    for (int i = a.first; i < a.last; ++i)
      for (int s = 0; s <= 20; ++s) {
        const Vec2 p = pts[i].head<2>() + (pts[i + 1].head<2>() - pts[i].head<2>()) * (s / 20.0);
        worst = std::max(worst, distance_to_arc(p, from, to, a.centre, a.clockwise));
      }
  }
  return worst;
}

void expect_cover(const std::vector<ArcPiece>& pieces, int n) {
  ASSERT_FALSE(pieces.empty());
  EXPECT_EQ(pieces.front().first, 0);
  EXPECT_EQ(pieces.back().last, n - 1);
  for (size_t i = 1; i < pieces.size(); ++i) EXPECT_EQ(pieces[i].first, pieces[i - 1].last);
}

}  // namespace

TEST(ArcFit, CircleSegmentsBecomeFewArcsWithinTolerance) {
  for (bool cw : {false, true}) {
    auto pts = circle(10, -5, 25, 0, cw ? -1.9 * M_PI : 1.9 * M_PI, 300, 3.0);
    const auto pieces = fit_arcs(pts, ArcFitOptions{});
    expect_cover(pieces, static_cast<int>(pts.size()));
    ASSERT_LE(pieces.size(), 2u);
    EXPECT_TRUE(pieces[0].arc);
    EXPECT_EQ(pieces[0].clockwise, cw);
    EXPECT_NEAR(pieces[0].centre.x(), 10, 1e-6);
    EXPECT_NEAR(pieces[0].radius, 25, 1e-6);
    EXPECT_LE(max_deviation(pts, pieces), 0.005 + 1e-9);
  }
}

TEST(ArcFit, CoarsePolygonKeepsItsChordsWhenTheSagittaExceedsTheTolerance) {
  // 36 segments on r = 25: the sagitta is 25 (1 - cos 5 deg) = 0.095 mm, over a 0.005 mm tolerance.
  auto pts = circle(0, 0, 25, 0, 2 * M_PI, 36);
  ArcFitOptions tight;
  const auto strict = fit_arcs(pts, tight);
  expect_cover(strict, 37);
  for (const auto& p : strict) EXPECT_FALSE(p.arc);
  ArcFitOptions loose;
  loose.tolerance = 0.1;
  const auto fitted = fit_arcs(pts, loose);
  expect_cover(fitted, 37);
  EXPECT_LE(fitted.size(), 3u);
  EXPECT_LE(max_deviation(pts, fitted), 0.1 + 1e-9);
}

TEST(ArcFit, NoiseStraightLinesAndSteps) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 0.001);
  auto pts = circle(0, 0, 40, 0, M_PI, 200);
  // One draw a statement: the order in which a call's arguments are evaluated is unspecified (GCC's differs from
  // clang's), and the noise must be the same whichever compiler built the test.
  for (auto& p : pts) {
    const double dy = noise(rng);
    const double dx = noise(rng);
    p += Vec3(dx, dy, 0);
  }
  auto pieces = fit_arcs(pts, ArcFitOptions{});
  expect_cover(pieces, static_cast<int>(pts.size()));
  EXPECT_LE(max_deviation(pts, pieces), 0.005 + 1e-9);
  size_t arcs = 0;
  for (const auto& p : pieces) arcs += p.arc;
  EXPECT_GE(arcs, 1u);
  EXPECT_LE(pieces.size(), 10u);

  std::vector<Vec3> line;
  for (int i = 0; i <= 20; ++i) line.emplace_back(i, 2 * i, 0);
  pieces = fit_arcs(line, ArcFitOptions{});
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_FALSE(pieces[0].arc);

  // A circle that changes height midway is not one planar arc.
  auto stepped = circle(0, 0, 20, 0, M_PI, 60);
  for (size_t i = 30; i < stepped.size(); ++i) stepped[i].z() = -0.5;
  for (const auto& p : fit_arcs(stepped, ArcFitOptions{}))
    if (p.arc) {
      EXPECT_TRUE(p.last <= 30 || p.first >= 30) << p.first << ".." << p.last;
    }
  // An S-curve splits where the turning changes direction.
  auto s1 = circle(0, 0, 10, M_PI, 0, 50);
  auto s2 = circle(20, 0, 10, M_PI, 2 * M_PI, 50);
  s1.insert(s1.end(), s2.begin() + 1, s2.end());
  pieces = fit_arcs(s1, ArcFitOptions{});
  expect_cover(pieces, static_cast<int>(s1.size()));
  EXPECT_LE(max_deviation(s1, pieces), 0.005 + 1e-9);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_NE(pieces[0].clockwise, pieces[1].clockwise);
}

TEST(ArcPost, FineContoursTakeFewerBlocks) {
  // The dome's contours at 360 segments per circle (fine chords): arcs replace most of the lines.
  Job job{test::revolution_contours("dome", [](double z) { return std::sqrt(std::max(0.0, 2500 - z * z)); }, 50, 5, 360)};
  PostOptions lines, arcs;
  arcs.arcs = true;
  const Program a = post(job, lines), b = post(job, arcs);
  EXPECT_LT(b.motion_blocks() * 10, a.motion_blocks()) << a.motion_blocks() << " -> " << b.motion_blocks();
  size_t g2g3 = 0;
  for (const auto& l : b.lines) g2g3 += l.rfind("G2", 0) == 0 || l.rfind("G3", 0) == 0 || l.find(" I") != std::string::npos;
  EXPECT_GT(g2g3, 0u);
}

namespace {

// The number of arcs, after checking coverage and the two-sided deviation.
size_t checked_arcs(const std::vector<Vec3>& pts, double tolerance, const std::string& what) {
  ArcFitOptions o;
  o.tolerance = tolerance;
  const auto pieces = fit_arcs(pts, o);
  expect_cover(pieces, static_cast<int>(pts.size()));
  EXPECT_LE(max_deviation(pts, pieces), tolerance + 1e-9) << what << " at " << tolerance;
  size_t arcs = 0;
  for (const auto& p : pieces) arcs += p.arc;
  return arcs;
}

}  // namespace

TEST(ArcFit, CurvesThatAreNoCirclesStayWithinTheTolerance) {
  for (double tol : {0.005, 0.05}) {
    // Ellipse 30 x 18, 2000 points: pieced together from arcs, each within the tolerance.
    std::vector<Vec3> ellipse;
    for (int i = 0; i <= 2000; ++i) {
      const double a = 2 * M_PI * i / 2000 * 0.99;
      ellipse.emplace_back(30 * std::cos(a), 18 * std::sin(a), -2);
    }
    const size_t arcs = checked_arcs(ellipse, tol, "ellipse");
    EXPECT_GT(arcs, 4u);
    EXPECT_LT(arcs, 400u);
    // Archimedean spiral r = 5 + 2 theta over three turns.
    std::vector<Vec3> spiral;
    for (int i = 0; i <= 3000; ++i) {
      const double t = 6 * M_PI * i / 3000;
      spiral.emplace_back((5 + 2 * t) * std::cos(t), (5 + 2 * t) * std::sin(t), 0);
    }
    EXPECT_GT(checked_arcs(spiral, tol, "spiral"), 3u);
    // A sine wave: turns both ways; every arc stays on one side of an inflection.
    std::vector<Vec3> sine;
    for (int i = 0; i <= 1000; ++i) sine.emplace_back(0.1 * i, 8 * std::sin(0.1 * i / 7), 1);
    checked_arcs(sine, tol, "sine");
    // A random walk: whatever the fitter does, it stays within the tolerance.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> step(-1, 1);
    std::vector<Vec3> walk{Vec3::Zero()};
    for (int i = 0; i < 500; ++i) walk.push_back(walk.back() + Vec3(step(rng), step(rng), 0));
    checked_arcs(walk, tol, "random walk");
    // A zig-zag (no two consecutive turns the same way) has no arc.
    std::vector<Vec3> zigzag;
    for (int i = 0; i <= 100; ++i) zigzag.emplace_back(i, i % 2 ? 0.5 : 0.0, 0);
    EXPECT_EQ(checked_arcs(zigzag, tol, "zigzag"), 0u);
  }
}

TEST(ArcFit, RoundedCornersBecomeArcsAroundTheirCentres) {
  // A 40 x 20 rectangle with corners of radius 5 (24 chords each, sagitta 0.0027 mm), as an offset contour of a
  // flat end mill.
  std::vector<Vec3> pts;
  const Vec2 centres[4] = {Vec2(35, 5), Vec2(35, 15), Vec2(5, 15), Vec2(5, 5)};
  for (int c = 0; c < 4; ++c) {
    const double a0 = -M_PI / 2 + c * M_PI / 2;
    for (int i = 0; i <= 24; ++i) {
      const double a = a0 + (M_PI / 2) * i / 24;
      pts.emplace_back(centres[c].x() + 5 * std::cos(a), centres[c].y() + 5 * std::sin(a), -1);
    }
  }
  pts.push_back(pts.front());
  ArcFitOptions o;
  o.tolerance = 0.005;
  const auto pieces = fit_arcs(pts, o);
  expect_cover(pieces, static_cast<int>(pts.size()));
  EXPECT_LE(max_deviation(pts, pieces), 0.005 + 1e-9);
  size_t arcs = 0;
  for (const auto& p : pieces) {
    if (!p.arc) continue;
    ++arcs;
    EXPECT_NEAR(p.radius, 5, 1e-6);
    EXPECT_FALSE(p.clockwise);
    double nearest = INFINITY;
    for (const Vec2& c : centres) nearest = std::min(nearest, (p.centre - c).norm());
    EXPECT_LT(nearest, 1e-6);
  }
  EXPECT_EQ(arcs, 4u);
  EXPECT_EQ(pieces.size(), 8u);  // four arcs and the four straight sides
  // Tighter than the chords' sagitta: the corners keep their chords.
  o.tolerance = 0.002;
  for (const auto& p : fit_arcs(pts, o)) EXPECT_FALSE(p.arc);
}
