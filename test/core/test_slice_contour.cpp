// Contour toolpaths from slices: the cutter stays exactly one radius from the section, holes are cut inside,
// moves have the right kinds and feeds, climb and conventional run opposite ways.
#include <gtest/gtest.h>

#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/plan/contour_toolpath.hpp"

using namespace rosmill::core;

namespace {

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// Distance from p to the boundary of the closed contours of a layer.
double distance_to_section(const Vec2& p, const SliceLayer& layer) {
  double d = INFINITY;
  for (const Contour& c : layer.contours)
    for (size_t i = 0; i < c.points.size(); ++i)
      d = std::min(d, segment_distance(p, c.points[i], c.points[(i + 1) % c.points.size()]));
  return d;
}

Tool flat_tool(double diameter) {
  Tool t;
  t.cutter = Cutter::flat(diameter);
  t.feed = 1200;
  t.plunge_feed = 250;
  return t;
}

// Every feed move of every pass: its end point and the middle of the segment leading to it lie one radius from
// the section of its layer (the chords of a round join come closer by at most the arc tolerance).
void expect_one_radius_from_sections(const Mesh& mesh, const Toolpath& tp, double radius, double arc_tol) {
  ASSERT_FALSE(tp.passes.empty());
  for (const ToolpathPass& pass : tp.passes) {
    double z = NAN;
    for (const Move& m : pass.moves)
      if (m.type == MoveType::Plunge) z = m.to.z();
    ASSERT_FALSE(std::isnan(z));
    const SliceLayer layer = slice_mesh(mesh, {z})[0];
    Vec3 prev = pass.moves.front().to;
    for (const Move& m : pass.moves) {
      if (m.type == MoveType::Feed) {
        EXPECT_EQ(m.to.z(), z);
        const double d_end = distance_to_section(m.to.head<2>(), layer);
        const double d_mid = distance_to_section(0.5 * (m.to + prev).head<2>(), layer);
        EXPECT_NEAR(d_end, radius, 2e-6) << pass.name;
        EXPECT_GE(d_mid, radius - arc_tol - 2e-6) << pass.name;
        EXPECT_LE(d_mid, radius + 2e-6) << pass.name;
      }
      prev = m.to;
    }
  }
}

}  // namespace

TEST(SliceContour, CylinderLoopsAreOneRadiusOutside) {
  const Mesh m = make_primitive("cylinder");
  ContourOptions o;
  o.stepdown = 15;
  const Toolpath tp = contour_toolpath(m, flat_tool(6), o);
  ASSERT_EQ(tp.passes.size(), 4u);  // 45, 30, 15, 0
  expect_one_radius_from_sections(m, tp, 3.0, o.arc_tolerance);
}

TEST(SliceContour, CavityPocketLoopIsOneRadiusInsideTheHole) {
  const Mesh m = make_primitive("cavity");
  ContourOptions o;
  o.stepdown = 10;
  o.arc_tolerance = 0.005;
  const Toolpath tp = contour_toolpath(m, flat_tool(10), o);
  expect_one_radius_from_sections(m, tp, 5.0, o.arc_tolerance);
  // At z = 30 the pocket's radius is sqrt(50^2 - 30^2) = 40: one loop outside the block, one inside the pocket.
  const ToolpathPass* layer30 = nullptr;
  for (const ToolpathPass& p : tp.passes)
    if (p.name == "contour z=30.000000") layer30 = &p;
  ASSERT_NE(layer30, nullptr);
  size_t plunges = 0;
  double inner_max = 0;
  for (const Move& mv : layer30->moves) {
    plunges += mv.type == MoveType::Plunge;
    const double r = mv.to.head<2>().norm();
    if (mv.type == MoveType::Feed && r < 50) inner_max = std::max(inner_max, r);
  }
  EXPECT_EQ(plunges, 2u);
  EXPECT_LE(inner_max, 40.0 - 5.0 + 1e-6);
  EXPECT_GT(inner_max, 30.0);
}

TEST(SliceContour, MovesRetractBetweenLoopsAndUseTheToolsFeeds) {
  const Mesh m = make_primitive("cavity");
  ContourOptions o;
  o.stepdown = 20;
  const Tool tool = flat_tool(8);
  const Toolpath tp = contour_toolpath(m, tool, o);
  EXPECT_EQ(tp.strategy, "contour");
  EXPECT_EQ(tp.safe_z, 65.0);
  for (const ToolpathPass& pass : tp.passes) {
    const auto& mv = pass.moves;
    for (size_t i = 0; i < mv.size(); ++i) {
      if (mv[i].type == MoveType::Plunge) {
        ASSERT_GT(i, 0u);
        EXPECT_EQ(mv[i - 1].type, MoveType::Rapid);
        EXPECT_EQ(mv[i - 1].to.z(), tp.safe_z);
        EXPECT_EQ(mv[i].feed, tool.plunge_feed);
      }
      if (mv[i].type == MoveType::Feed) {
        EXPECT_EQ(mv[i].feed, tool.feed);
      }
      if (mv[i].type == MoveType::Rapid) {
        EXPECT_EQ(mv[i].to.z(), tp.safe_z);
      }
    }
    EXPECT_EQ(mv.back().type, MoveType::Rapid) << "every loop ends with a retract";
  }
}

TEST(SliceContour, ClimbAndConventionalRunOppositeWays) {
  const Mesh m = make_primitive("cube");
  ContourOptions o;
  o.stepdown = 30;
  auto turning = [&](bool climb) {
    o.climb = climb;
    const Toolpath tp = contour_toolpath(m, flat_tool(6), o);
    std::vector<Vec2> loop;
    for (const Move& mv : tp.passes.at(0).moves)
      if (mv.type == MoveType::Feed) loop.push_back(mv.to.head<2>());
    return signed_area(loop);
  };
  // Around material: climb with an M3 spindle runs clockwise; the loop's area is the square grown by 3 mm with
  // rounded corners.
  const double area = 66.0 * 66.0 - (4 - M_PI) * 9.0;
  EXPECT_NEAR(turning(true), -area, 0.05);
  EXPECT_NEAR(turning(false), area, 0.05);
}

TEST(SliceContour, StrategyTableRunsContour) {
  const Mesh m = make_primitive("dome");
  PlanningRequest r;
  r.input.mesh = &m;
  r.strategy = "contour";
  PlanParams& p = r.params;
  p.tool = flat_tool(6);
  p.stepdown = 10;
  const Job job = plan(r);
  ASSERT_EQ(job.size(), 1u);
  EXPECT_EQ(job[0].passes.size(), 5u);  // 40, 30, 20, 10, 0
  expect_one_radius_from_sections(m, job[0], 3.0, p.tolerance);
  p.tool.cutter = Cutter::ball(6);
  EXPECT_THROW(plan(r), Error);
  p.tool.cutter = Cutter::flat(6);
  bool asked = false;
  r.progress = [&](double) { return asked = true, false; };
  EXPECT_THROW(plan(r), Error);
  EXPECT_TRUE(asked);
}

TEST(SliceContour, OverhangIsClearedByTheSectionsAbove) {
  // A mushroom: a thin stem under a wide cap. At the stem's layer the cutter must stay outside the cap.
  std::vector<Vec3> stem = cube_corners(1.0), cap = cube_corners(1.0);
  for (Vec3& p : stem) p = Vec3(20 + 20 * p.x(), 20 + 20 * p.y(), 30 * p.z());
  for (Vec3& p : cap) p = Vec3(60 * p.x(), 60 * p.y(), 30 + 30 * p.z());
  stem.insert(stem.end(), cap.begin(), cap.end());
  const Mesh m = build_mesh(stem);
  ContourOptions o;
  o.stepdown = 15;
  const Toolpath tp = contour_toolpath(m, flat_tool(6), o);
  ASSERT_EQ(tp.passes.size(), 4u);  // 45, 30, 15, 0
  for (const ToolpathPass& pass : tp.passes)
    for (const Move& mv : pass.moves) {
      const Vec2 p = mv.to.head<2>();
      const Vec2 nearest = p.cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(60, 60));
      EXPECT_GE((p - nearest).norm(), 3.0 - o.arc_tolerance) << pass.name << " at " << p.transpose();
    }
}
