// Waterline: closed CL loops at the exact level, clear of the part (the independent reference over all
// triangles at every loop point and every 0.1 mm along the moves), and sane at the height of a flat face:
// pycam-textbox.stl at z = -5.000, where OpenCAMLib returns hundreds of junk loops. The loops from the mesh's own
// answers to "held above the level?" are those of its exact drops.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/checked_surface.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/plan/waterline.hpp"
#include "rosmill/testing/reference_drop.hpp"
#include "rosmill/testing/sanitized.hpp"
#include "test_plan_check.hpp"

using namespace rosmill::core;
using namespace rosmill::core::test;

namespace {

struct Levels {
  Toolpath tp;
  std::vector<std::vector<Loop>> loops;
};

Levels waterline(const Mesh& mesh, const Cutter& c, const std::vector<double>& levels, double allowance = 0.0) {
  PlanParams p;
  p.tool = default_tool(c);
  p.allowance = allowance;
  WaterlineOptions o;
  o.levels = levels;
  Levels out;
  const Job job = waterline_on(MeshSurface(mesh), p, o, {}, &out.loops);
  EXPECT_EQ(job.size(), 1u);
  out.tp = job.at(0);
  return out;
}

// Every loop: at least three points, all at exactly the level and each on the contour (the cutter grown by
// 0.01 mm touches part + allowance; the gouge check proves it clear of them). The chords, the closing one (last
// to first) included, are probed at a quarter, half and three quarters: almost all of those points are on the
// contour too. A chain that did not close would show as a closing chord across free space or through the part.
// (Not all: the loop refinement checks chord midpoints only, so where two arcs of the contour meet a chord can
// stand off it by more than 0.01 mm, on the free side.)
void expect_loops_on_contour(const std::vector<Loop>& loops, double z, const Mesh& mesh, const Cutter& c,
                             double allowance, const std::string& what) {
  constexpr double kNear = 0.01;
  const Cutter grown = grown_by_hand(c, allowance + kNear);
  std::vector<Vec3> probes;
  std::vector<char> vertex;
  for (const Loop& loop : loops) {
    ASSERT_GE(loop.size(), 3u) << what;
    for (size_t k = 0; k < loop.size(); ++k) {
      EXPECT_EQ(loop[k].z(), z) << what;
      if (k % rosmill::testing::kReferenceStride != 0) continue;  // every 16th chord under the sanitizers
      const Vec3 &a = loop[k], &b = loop[(k + 1) % loop.size()];
      for (double f : {0.0, 0.25, 0.5, 0.75}) probes.push_back(a + f * (b - a)), vertex.push_back(f == 0.0);
    }
  }
  std::vector<char> touches(probes.size());
  tbb::parallel_for(size_t(0), probes.size(), [&](size_t i) {
    touches[i] = reference_gouges(grown, mesh, probes[i] - Vec3(0, 0, allowance + kNear), 0.0);
  });
  size_t off = 0;
  for (size_t i = 0; i < probes.size(); ++i) {
    if (vertex[i]) EXPECT_TRUE(touches[i]) << what << ": loop point " << probes[i].transpose() << " off the contour";
    else off += !touches[i];
  }
  std::printf("  %s: %zu loops, %zu chord points probed, %zu off the contour by more than %.2f mm\n", what.c_str(),
              loops.size(), probes.size(), off, kNear);
  EXPECT_LE(off, probes.size() / 100) << what;
}

}  // namespace

TEST(PlanWaterline, TextboxAtTheFlatFaceHeightGivesFewClosedLoops) {
  const Mesh box = read_stl(ROSMILL_TEST_DATA "/pycam-textbox.stl");
  const Cutter ball = Cutter::ball(6);
  for (double z : {-5.0, -6.0}) {  // the flat face's height and one below it
    const Levels w = waterline(box, ball, {z});
    ASSERT_EQ(w.loops.size(), 1u);
    EXPECT_GE(w.loops[0].size(), 1u) << z;
    EXPECT_LE(w.loops[0].size(), 20u) << z;  // the outline and the letters' islands, not hundreds of scraps
    expect_loops_on_contour(w.loops[0], z, box, ball, 0.0, "textbox z " + std::to_string(z));
    expect_no_gouge(w.tp, box, 0.0, "textbox waterline z " + std::to_string(z));
  }
}

TEST(PlanWaterline, ClosedAndClearOnModelsAndPrimitives) {
  StlReadOptions inch;
  inch.units = Units::Inch;
  const Mesh kt = read_stl(ROSMILL_TEST_DATA "/ktoolcav.stl", inch);
  const Mesh rush = read_stl(ROSMILL_TEST_DATA "/mount_rush.stl");
  const Mesh cone = make_primitive("cone");
  struct Case {
    const char* name;
    const Mesh& mesh;
    Cutter cutter;
    double allowance;
  };
  for (const Case& c : {Case{"ktoolcav (inch) ball 6", kt, Cutter::ball(6), 0.3},
                        Case{"mount_rush bull 8 r1", rush, Cutter::bull(8, 1), 0.0},
                        Case{"cone flat 10", cone, Cutter::flat(10), 0.5}}) {
    const double zmin = c.mesh.bbox.min.z(), zmax = c.mesh.bbox.max.z();
    const std::vector<double> levels = {zmin + 0.3 * (zmax - zmin), zmin + 0.7 * (zmax - zmin)};
    const Levels w = waterline(c.mesh, c.cutter, levels, c.allowance);
    size_t loops = 0;
    for (size_t i = 0; i < levels.size(); ++i) {
      expect_loops_on_contour(w.loops[i], levels[i], c.mesh, c.cutter, c.allowance, c.name);
      loops += w.loops[i].size();
    }
    EXPECT_GE(loops, 2u) << c.name;
    expect_no_gouge(w.tp, c.mesh, c.allowance, c.name);
  }
}

namespace {

// The mesh's drops only: held_above and the level probe are Surface's defaults, which drop the cutter and
// compare, the way the waterline asked before the mesh answered those questions itself.
class DropsOnly : public Surface {
 public:
  explicit DropsOnly(const MeshSurface& s) : s_(s) {}
  Box3 bounds() const override { return s_.bounds(); }
  Drop drop(const Cutter& c, double x, double y) const override { return s_.drop(c, x, y); }
  void drop_many(const Cutter& c, const Vec2* xy, size_t n, Drop* out) const override { s_.drop_many(c, xy, n, out); }

 private:
  const MeshSurface& s_;
};

double distance_to_loops(const Vec3& p, const std::vector<Loop>& loops) {
  double best = 1e300;
  for (const Loop& loop : loops)
    for (size_t k = 0; k < loop.size(); ++k) {
      const Vec3 &a = loop[k], &b = loop[(k + 1) % loop.size()];
      const Vec3 ab = b - a;
      const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      best = std::min(best, (a + t * ab - p).norm());
    }
  return best;
}

// Hausdorff distance between two sets of closed loops, vertices to the other side's chords, both ways.
double hausdorff(const std::vector<Loop>& a, const std::vector<Loop>& b) {
  double d = 0;
  for (const Loop& loop : a)
    for (const Vec3& p : loop) d = std::max(d, distance_to_loops(p, b));
  for (const Loop& loop : b)
    for (const Vec3& p : loop) d = std::max(d, distance_to_loops(p, a));
  return d;
}

}  // namespace

// The mesh answers "is the tip held above the level?" without the exact drop (a bound that starts at the level,
// triangles gathered once per place): the loops are those of the drops, at OpenCAMLib's three levels.
TEST(PlanWaterline, LoopsOfTheMeshQuestionsEqualTheLoopsOfTheDrops) {
  for (const char* file : {"pycam-textbox.stl", "mount_rush.stl", "failedinpycam.stl"}) {
    const Mesh mesh = read_stl(std::string(ROSMILL_TEST_DATA) + "/" + file);
    const MeshSurface surface(mesh);
    PlanParams p;
    p.tool = default_tool(Cutter::ball(6));
    p.tolerance = 0.01;
    WaterlineOptions o;
    const double zmin = mesh.bbox.min.z(), zmax = mesh.bbox.max.z();
    for (double f : {0.25, 0.5, 0.75})  // under the sanitizers, the middle level only
      if (!rosmill::testing::kSanitized || f == 0.5) o.levels.push_back(zmin + f * (zmax - zmin));
    std::vector<std::vector<Loop>> fast, drops;
    waterline_on(surface, p, o, {}, &fast);
    waterline_on(DropsOnly(surface), p, o, {}, &drops);
    ASSERT_EQ(fast.size(), drops.size());
    for (size_t i = 0; i < fast.size(); ++i) {
      ASSERT_EQ(fast[i].size(), drops[i].size()) << file << " level " << o.levels[i];
      ASSERT_FALSE(fast[i].empty()) << file << " level " << o.levels[i];
      const double h = hausdorff(fast[i], drops[i]);
      EXPECT_LE(h, p.tolerance) << file << " level " << o.levels[i];
      std::printf("  %s z %.3f: %zu loops, Hausdorff distance %.3g mm\n", file, o.levels[i], fast[i].size(), h);
    }
  }
}

// What holds the cutter beyond the part (a check box, as a job's fixture is, reaching far past the grid the waterline
// contours): its contour runs off the grid and stays open there, never closed by a chord across the box. Every feed
// of the toolpath, sampled every 0.1 mm, keeps the cutter clear of the part and the box (the independent reference
// over all their triangles). The 40 x 30 mm block stands in a frame 70 mm long beside it.
TEST(PlanWaterline, AContourRunningOffTheGridIsLeftOpen) {
  const Mesh block = build_mesh(box_corners(Box3::between(Vec3(0, 0, 0), Vec3(40, 30, 20))));
  const Mesh frame = build_mesh(box_corners(Box3::between(Vec3(-30, 33, 0), Vec3(70, 40, 25))));
  const MeshSurface part(block), check(frame);
  const CheckedSurface both(part, check);
  PlanParams p;
  p.tool = default_tool(Cutter::flat(6));
  WaterlineOptions o;
  o.levels = {10.0};
  std::vector<std::vector<Loop>> loops;
  const Toolpath tp = waterline_on(both, p, o, {}, &loops).at(0);
  ASSERT_FALSE(loops[0].empty());
  std::vector<Vec3> corners = box_corners(Box3::between(Vec3(0, 0, 0), Vec3(40, 30, 20)));
  const std::vector<Vec3> frame_corners = box_corners(Box3::between(Vec3(-30, 33, 0), Vec3(70, 40, 25)));
  corners.insert(corners.end(), frame_corners.begin(), frame_corners.end());
  const Mesh solids = build_mesh(corners);
  Vec3 at = tp.start;
  size_t checked = 0;
  for (const ToolpathPass& pass : tp.passes)
    for (const Move& m : pass.moves) {
      if (m.type == MoveType::Feed && std::abs(m.to.z() - 10.0) < 1e-9 && std::abs(at.z() - 10.0) < 1e-9) {
        const int n = std::max(1, static_cast<int>(std::ceil((m.to - at).norm() / 0.1)));
        for (int k = 0; k <= n; ++k) {
          const Vec3 q = at + (m.to - at) * (double(k) / n);
          EXPECT_LE(reference_drop(p.tool.cutter, solids, q.x(), q.y()), 10.0 + 1e-6) << q.transpose();
          ++checked;
        }
      }
      at = m.to;
    }
  EXPECT_GT(checked, 1000u);
}
