// Raster finishing: no gouge on real models and the seed primitives (every CL and every 0.1 mm along every move
// against the independent reference over all triangles), CL points exactly on part + allowance, chords within
// the tolerance, zigzag and one-way linking, and a boundary (a polygon, a segmentation patch).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/plan/raster.hpp"
#include "rosmill/segment/surface_patches.hpp"
#include "rosmill/slice/slicer.hpp"
#include "rosmill/toolpath/toolpath_stats.hpp"
#include "rosmill/testing/sanitized.hpp"
#include "test_plan_check.hpp"

using namespace rosmill::core;
using namespace rosmill::core::test;

namespace {

PlanParams params_for(const Cutter& c, double stepover, double allowance = 0.0, double angle = 0.0) {
  PlanParams p;
  p.tool = default_tool(c);
  p.stepover = stepover;
  p.allowance = allowance;
  p.angle_deg = angle;
  return p;
}

Toolpath raster(const Mesh& mesh, const PlanParams& p, const RasterOptions& o = {}) {
  const MeshSurface s(mesh);
  const Job job = raster_on(s, p, o);
  EXPECT_EQ(job.size(), 1u);
  return job.at(0);
}

Mesh ktoolcav_mm() {
  StlReadOptions inch;
  inch.units = Units::Inch;
  return read_stl(ROSMILL_TEST_DATA "/ktoolcav.stl", inch);
}

// Feed moves (not plunges) whose two ends differ horizontally: the cutting chords.
template <class F>
void for_each_chord(const Toolpath& tp, F f) {
  Vec3 at = tp.start;
  for (const auto& pass : tp.passes)
    for (const Move& m : pass.moves) {
      if (m.type == MoveType::Feed && (m.to - at).head<2>().norm() > 1e-5) f(at, m.to);
      at = m.to;
    }
}

}  // namespace

TEST(PlanRaster, NoGougeOnRealModels) {
  expect_no_gouge(raster(read_stl(ROSMILL_TEST_DATA "/mount_rush.stl"), params_for(Cutter::ball(6), 3.0)),
                  read_stl(ROSMILL_TEST_DATA "/mount_rush.stl"), 0.0, "mount_rush ball 6");
  const Mesh box = read_stl(ROSMILL_TEST_DATA "/pycam-textbox.stl");
  expect_no_gouge(raster(box, params_for(Cutter::flat(6), 4.0, 0.5, 30.0)), box, 0.5, "textbox flat 6 allowance 0.5");
  const Mesh wheel = read_stl(ROSMILL_TEST_DATA "/wheel_in_box.stl");
  expect_no_gouge(raster(wheel, params_for(Cutter::bull(8, 1), 12.0, 0.0, 90.0)), wheel, 0.0, "wheel bull 8 r1");
  const Mesh kt = ktoolcav_mm();
  expect_no_gouge(raster(kt, params_for(Cutter::ball(6), 4.0, 0.3)), kt, 0.3, "ktoolcav (inch) ball 6");
}

TEST(PlanRaster, NoGougeOnPrimitives) {
  for (const std::string& name : primitive_names()) {
    const Mesh m = make_primitive(name);
    // Coarse stepovers keep the check quick; the walls, rims and edges are crossed all the same. Inside the
    // cavity the reference is slow (the ball nearly fits the hollow, so little is pruned): points along its
    // moves are checked every 0.4 mm there, every CL point still.
    const bool cavity = name == "cavity";
    expect_no_gouge(raster(m, params_for(Cutter::ball(6), cavity ? 15.0 : 11.0, 0.2, 15.0)), m, 0.2,
                    name + " ball 6", kGougeTolerance, cavity ? 0.4 : kAlongMoveStep);
    if (name == "cube" || name == "cone")  // the flat cutter's rim on a wall's edge and on a slope
      expect_no_gouge(raster(m, params_for(Cutter::flat(10), 17.0)), m, 0.0, name + " flat 10");
  }
}

// Every cutting chord's end points touch part + allowance (the drop is exact), and points a quarter, a half and
// three quarters along it lie within the tolerance of the true CL height (adaptive sampling); the steps over
// walls lie above it and are a small part of the path.
TEST(PlanRaster, ChordsWithinToleranceOfTheSurface) {
  const Mesh m = read_stl(ROSMILL_TEST_DATA "/mount_rush.stl");
  const double allowance = 0.25, tol = 0.01;
  PlanParams p = params_for(Cutter::ball(6), 6.0, allowance, 45.0);
  p.tolerance = tol;
  const Toolpath tp = raster(m, p);
  const Cutter grown = grown_by_hand(p.tool.cutter, allowance);
  const double floor = m.bbox.min.z() + allowance;
  auto true_cl = [&](const Vec3& q) { return std::max(reference_drop(grown, m, q.x(), q.y()) + allowance, floor); };
  std::vector<std::pair<Vec3, Vec3>> chords;
  for_each_chord(tp, [&](const Vec3& a, const Vec3& b) { chords.emplace_back(a, b); });
  ASSERT_GT(chords.size(), 1000u);
  rosmill::testing::thin_reference_samples(chords);  // every 16th under the sanitizers
  // Signed errors (path minus true CL): below is towards the part. A step over a wall (plan_support.hpp) is a
  // level chord that lies above the CL on purpose; every other chord ends on the CL.
  std::vector<double> end_error(chords.size()), below(chords.size()), above(chords.size());
  tbb::parallel_for(size_t(0), chords.size(), [&](size_t i) {
    const auto& [a, b] = chords[i];
    end_error[i] = b.z() - true_cl(b);
    below[i] = std::max(0.0, -end_error[i]);
    above[i] = std::max(0.0, end_error[i]);
    for (double f : {0.25, 0.5, 0.75}) {
      const Vec3 q = a + f * (b - a);
      const double e = q.z() - true_cl(q);
      below[i] = std::max(below[i], -e), above[i] = std::max(above[i], e);
    }
  });
  double chord_length = 0, step_length = 0, worst_below = 0, worst_above = 0, worst_end = 0;
  size_t steps = 0;
  for (size_t i = 0; i < chords.size(); ++i) {
    const auto& [a, b] = chords[i];
    const double len = (b - a).head<2>().norm();
    chord_length += len;
    worst_below = std::max(worst_below, below[i]);
    EXPECT_LE(below[i], tol) << a.transpose() << " to " << b.transpose();
    if (a.z() == b.z() && above[i] > tol) {  // a step over a wall: level, above the CL
      ++steps, step_length += len;
      continue;
    }
    worst_above = std::max(worst_above, above[i]), worst_end = std::max(worst_end, std::abs(end_error[i]));
    EXPECT_LE(std::abs(end_error[i]), 1e-6) << b.transpose();
    EXPECT_LE(above[i], tol) << a.transpose() << " to " << b.transpose();
  }
  std::printf("  %zu chords, %.1f mm; %zu steps over walls, %.2f mm; worst below %.2g, above %.2g, end %.2g\n",
              chords.size(), chord_length, steps, step_length, worst_below, worst_above, worst_end);
  EXPECT_LT(step_length, 0.01 * chord_length);  // steps over walls are short: the rest follows the CL
  // Adaptive: flat stretches need few points, the relief many; a coarse tolerance needs fewer than a fine one.
  PlanParams fine = p;
  fine.tolerance = 0.001;
  size_t coarse_moves = tp.move_count(), fine_moves = raster(m, fine).move_count();
  EXPECT_GT(fine_moves, coarse_moves * 3 / 2) << coarse_moves << " vs " << fine_moves;
}

// Zigzag alternates the direction and links along the surface; one-way cuts every line the same way with a
// retract in between.
TEST(PlanRaster, ZigzagAndOneWay) {
  const Mesh m = make_primitive("dome");
  const PlanParams p = params_for(Cutter::ball(6), 5.0);
  auto cuts = [](const Toolpath& tp, int* rapids) {
    std::vector<double> dirs;  // x direction of each horizontal run of feed moves between retracts or links
    *rapids = 0;
    Vec3 at = tp.start;
    for (const auto& pass : tp.passes)
      for (const Move& m : pass.moves) {
        if (m.type == MoveType::Rapid) ++*rapids;
        if (m.type == MoveType::Feed && std::abs(m.to.x() - at.x()) > 1.0) {
          const double d = m.to.x() > at.x() ? 1 : -1;
          if (dirs.empty() || dirs.back() != d) dirs.push_back(d);
        }
        at = m.to;
      }
    return dirs;
  };
  int zz_rapids = 0, ow_rapids = 0;
  const Toolpath zz = raster(m, p);
  RasterOptions one_way;
  one_way.zigzag = false;
  const Toolpath ow = raster(m, p, one_way);
  const std::vector<double> zz_dirs = cuts(zz, &zz_rapids), ow_dirs = cuts(ow, &ow_rapids);
  const size_t lines = static_cast<size_t>(std::ceil((100.0 + 6.0) / 5.0)) + 1;
  EXPECT_EQ(zz_dirs.size(), lines);  // the direction changes on every line
  EXPECT_EQ(ow_dirs.size(), 1u);     // always the same way
  EXPECT_LE(zz_rapids, 3);           // one approach and the final retract
  EXPECT_GE(ow_rapids, int(2 * (lines - 1)));  // up and across before each line
  expect_no_gouge(ow, m, 0.0, "dome one-way");
}

// A polygon boundary: every cutting move keeps the axis inside, and the lines cover it.
TEST(PlanRaster, PolygonBoundaryKeepsTheAxisInside) {
  const Mesh m = read_stl(ROSMILL_TEST_DATA "/mount_rush.stl");
  RasterOptions o;
  // An L-shaped outline with a square hole.
  o.boundary = {{Vec2(-30, -20), Vec2(30, -20), Vec2(30, 0), Vec2(0, 0), Vec2(0, 15), Vec2(-30, 15)},
                {Vec2(-20, -12), Vec2(-10, -12), Vec2(-10, -2), Vec2(-20, -2)}};
  const Toolpath tp = raster(m, params_for(Cutter::ball(6), 1.5), o);
  size_t inside = 0;
  Box3 cut;
  for_each_chord(tp, [&](const Vec3& a, const Vec3& b) {
    for (double f : {0.0, 0.5, 1.0}) {
      const Vec2 q = (a + f * (b - a)).head<2>();
      // On the outline itself counts as inside.
      EXPECT_TRUE(inside_region(o.boundary, q) || inside_region(o.boundary, q + Vec2(1e-7, 1e-7)) ||
                  inside_region(o.boundary, q - Vec2(1e-7, 1e-7)))
          << q.transpose();
      ++inside;
    }
    cut.add(a), cut.add(b);
  });
  EXPECT_GT(inside, 1000u);
  EXPECT_NEAR(cut.min.x(), -30, 1e-6);
  EXPECT_NEAR(cut.max.x(), 30, 1e-6);
  EXPECT_LE(cut.min.y(), -20 + 1.5);
  EXPECT_GE(cut.max.y(), 15 - 1.5);
  expect_no_gouge(tp, m, 0.0, "mount_rush inside an L");
}

// A segmentation patch as the boundary: the cube's top face (a patch of the phase 1 flooding) is machined, and
// nothing outside its outline.
TEST(PlanRaster, SegmentationPatchAsBoundary) {
  const Mesh m = make_primitive("cube");
  const segment::SurfacePatches patches = segment::segment_surface(m);
  ASSERT_EQ(patches.count(), 6u);
  const segment::Patch* top = nullptr;
  for (const segment::Patch& p : patches.patches())
    if (p.normal.z() > 0.99) top = &p;
  ASSERT_NE(top, nullptr);
  RasterOptions o;
  o.boundary = patch_region(m, *top);
  ASSERT_EQ(o.boundary.size(), 1u);
  EXPECT_NEAR(std::abs(signed_area(o.boundary[0])), 3600.0, 1e-9);
  const Toolpath tp = raster(m, params_for(Cutter::ball(6), 3.0), o);
  Box3 cut;
  for_each_chord(tp, [&](const Vec3& a, const Vec3& b) {
    cut.add(a), cut.add(b);
    EXPECT_NEAR(a.z(), 60.0, 1e-9);  // on the top face, never down the sides
  });
  EXPECT_NEAR(cut.min.x(), 0, 1e-9);
  EXPECT_NEAR(cut.max.x(), 60, 1e-9);
  expect_no_gouge(tp, m, 0.0, "cube top patch");
}

TEST(PlanRaster, AllowanceLiftsTheFlatFloor) {
  const Mesh m = make_primitive("cube");
  for (double a : {0.0, 0.5, 2.0}) {
    const Toolpath tp = raster(m, params_for(Cutter::flat(10), 4.0, a));
    size_t on_top = 0;
    for_each_chord(tp, [&](const Vec3& p, const Vec3& q) {
      for (double f = 0; f <= 1.0; f += 0.125) {
        const Vec3 c = p + f * (q - p);
        if (c.x() < 10 || c.x() > 50 || c.y() < 10 || c.y() > 50) continue;
        EXPECT_NEAR(c.z(), 60.0 + a, 1e-9);  // the cutter's flat bottom a above the top face
        ++on_top;
      }
    });
    EXPECT_GT(on_top, 5u);
    const Box3 b = tp.bounds();
    // Beside the walls the grown cutter stops a further `a` out.
    expect_no_gouge(tp, m, a, "cube flat 10 allowance " + std::to_string(a));
    EXPECT_LE(b.min.x(), -5 - a + 1e-9);
  }
}

// The models on which adaptive sampling once exploded (millions of moves, kilometres of up-and-down steps at
// walls, where a line runs at exactly the cutter's radius from an edge and the drop flickered between touching
// and not): the machine test's coarse settings (ball 6, stepover 6, tolerance 0.1). Planning is quick, the
// moves are a few per sampling step, the path is not much longer than the lines themselves, and nothing gouges
// deeper than that tolerance.
TEST(PlanRaster, BoundedAtWallsOfRealModels) {
  StlReadOptions inch;
  inch.units = Units::Inch;
  const std::pair<const char*, Mesh> models[] = {
      {"pycam-textbox", read_stl(ROSMILL_TEST_DATA "/pycam-textbox.stl")},
      {"featuretype (inch)", read_stl(ROSMILL_TEST_DATA "/featuretype.STL", inch)},
      {"ktoolcav (inch)", read_stl(ROSMILL_TEST_DATA "/ktoolcav.stl", inch)},
      {"wheel_in_box", read_stl(ROSMILL_TEST_DATA "/wheel_in_box.stl")},
  };
  PlanParams p = params_for(Cutter::ball(6), 6.0);
  p.tolerance = 0.1;
  for (const auto& [name, mesh] : models) {
    const auto t0 = std::chrono::steady_clock::now();
    const Toolpath tp = raster(mesh, p);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const ToolpathStats st = toolpath_stats(tp);
    // What the lines alone measure: the part's box grown by the radius, cut in lines a stepover apart, plus
    // the links between them.
    const Vec3 size = mesh.bbox.max - mesh.bbox.min;
    const double w = size.x() + 6.0, h = size.y() + 6.0;
    const double lines = w * (std::floor(h / 6.0) + 1) + h;
    const double sampling_steps = lines / std::min(0.25 * 3.0, 1.0);
    std::printf("  %s: %.3f s, %zu moves, cutting %.0f mm (lines %.0f mm), %.0f sampling steps\n", name, seconds,
                st.moves, st.cutting_length, lines, sampling_steps);
    EXPECT_LT(seconds, 5.0) << name;
    EXPECT_LT(double(st.moves), 2.0 * sampling_steps) << name;
    // Up and down walls adds at most twice the part's height per wall crossed; a few hundred crossings at most.
    EXPECT_LT(st.cutting_length, lines + 400 * size.z()) << name;
    EXPECT_GT(st.cutting_length, 0.9 * lines) << name;
    // The chords may pass the tolerance (0.1 here) below the true CL, not more.
    expect_no_gouge(tp, mesh, 0.0, std::string(name) + " ball 6 stepover 6 tolerance 0.1", p.tolerance);
  }
}
