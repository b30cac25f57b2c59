// CloudSurface: the drop-cutter against points (seed 004) for flat, ball and bull cutters, its grid index
// against brute force, the missing-data policy (lids over holes, support discs in sparse clouds), clouds sampled
// from the seed primitives and real models within the stated sampling bound of the mesh drop-cutter, and the
// engine's strategies running on a cloud through the Surface seam.
#include <gtest/gtest.h>

#include <random>

#include "rosmill/cloud/cloud_surface.hpp"
#include "rosmill/cloud/cloud_sweep.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "test_cloud_support.hpp"

using namespace rosmill::core;

namespace {

CloudSurfaceOptions bare() {
  CloudSurfaceOptions o;
  o.sampling_radius = 0.0;  // the seed's formula, no support discs
  return o;
}

std::vector<Vec3> level_grid(double size, double pitch, double z) {
  std::vector<Vec3> pts;
  for (double x = 0; x <= size + 1e-9; x += pitch)
    for (double y = 0; y <= size + 1e-9; y += pitch) pts.push_back(Vec3(x, y, z));
  return pts;
}

}  // namespace

TEST(CloudSurface, SinglePointFormulas) {
  const std::vector<Vec3> pts = {Vec3(0, 0, 10)};
  CloudSurfaceOptions o = bare();
  o.detect_holes = false;
  const CloudSurface s(pts, o);
  // Ball R = 3 at d = 2: z_p + sqrt(R² - d²) - R.
  EXPECT_NEAR(s.drop(Cutter::ball(6), 2, 0).z, 10 + std::sqrt(9.0 - 4.0) - 3, 1e-12);
  EXPECT_NEAR(s.drop(Cutter::ball(6), 0, 0).z, 10, 1e-12);
  EXPECT_NEAR(s.drop(Cutter::ball(6), 0, 2.999).z, 10 + std::sqrt(9.0 - 2.999 * 2.999) - 3, 1e-12);
  // Flat: z_p anywhere under the footprint, nothing outside (the floor, untouched).
  EXPECT_NEAR(s.drop(Cutter::flat(6), 2.9, 0).z, 10, 1e-12);
  EXPECT_TRUE(s.drop(Cutter::flat(6), 2.9, 0).touched);
  EXPECT_FALSE(s.drop(Cutter::flat(6), 3.1, 0).touched);
  EXPECT_EQ(s.drop(Cutter::flat(6), 3.1, 0).z, 10.0);
  // Bull D 6 r 1: flat inside Rf = 2, torus beyond: z_p - r + sqrt(r² - (d - Rf)²).
  EXPECT_NEAR(s.drop(Cutter::bull(6, 1), 1.9, 0).z, 10, 1e-12);
  EXPECT_NEAR(s.drop(Cutter::bull(6, 1), 2.5, 0).z, 10 - 1 + std::sqrt(1 - 0.25), 1e-12);
  EXPECT_NEAR(s.drop(Cutter::bull(6, 1), 0, 2.5).z, 10 - 1 + std::sqrt(1 - 0.25), 1e-12);
}

TEST(CloudSurface, SupportDiscsGrowTheFlatPartBySamplingRadiusLessTheAllowedSink) {
  const std::vector<Vec3> pts = {Vec3(0, 0, 10)};
  CloudSurfaceOptions o;
  o.detect_holes = false;
  o.sampling_radius = 1.0;
  o.max_sink = 0.01;
  const CloudSurface s(pts, o);
  // Ball R = 3: c = 1 - sqrt(2 * 3 * 0.01); the point holds the ball at its own height out to c, then the ball's
  // curve shifted out by c.
  const double c = 1.0 - std::sqrt(0.06);
  EXPECT_NEAR(s.support_radius(Cutter::ball(6)), c, 1e-12);
  EXPECT_NEAR(s.drop(Cutter::ball(6), c - 1e-6, 0).z, 10, 1e-9);
  EXPECT_NEAR(s.drop(Cutter::ball(6), 2, 0).z, 10 - 3 + std::sqrt(9 - (2 - c) * (2 - c)), 1e-12);
  EXPECT_TRUE(s.drop(Cutter::ball(6), 3 + c - 1e-6, 0).touched);
  EXPECT_FALSE(s.drop(Cutter::ball(6), 3 + c + 1e-6, 0).touched);
  // A flat end mill has no corner to sink with: its disc is the full sampling radius.
  EXPECT_NEAR(s.support_radius(Cutter::flat(10)), 1.0, 1e-12);
  EXPECT_TRUE(s.drop(Cutter::flat(10), 5.99, 0).touched);
  // A big corner sinks less than s over a gap of 1: no disc at all.
  EXPECT_EQ(s.support_radius(Cutter::ball(200)), 0.0);
}

TEST(CloudSurface, GridIndexMatchesBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 50), h(0, 8);
  std::vector<Vec3> pts;
  for (int i = 0; i < 20000; ++i) pts.push_back(Vec3(u(rng), u(rng), h(rng) + 0.1 * u(rng)));
  const cloudtest::SortedPoints brute(pts);
  std::vector<Vec2> xy;
  std::uniform_real_distribution<double> q(-5, 55);
  for (int i = 0; i < 300; ++i) xy.push_back(Vec2(q(rng), q(rng)));
  for (double radius : {0.0, 0.4}) {
    CloudSurfaceOptions o;
    o.detect_holes = false;
    o.sampling_radius = radius;
    const CloudSurface s(pts, o);
    for (const Cutter& c : {Cutter::flat(10), Cutter::ball(5), Cutter::bull(8, 2), Cutter::ball(0.5)}) {
      // The reference: the lowest tip of the supported cutter that no point enters, over every point.
      const Cutter seen = s.supported(c);
      std::vector<Drop> many(xy.size());
      s.drop_many(c, xy.data(), xy.size(), many.data());
      for (size_t i = 0; i < xy.size(); ++i) {
        const double ref = brute.penetration(seen, Vec3(xy[i].x(), xy[i].y(), 0.0));
        const Drop d = s.drop(c, xy[i].x(), xy[i].y());
        if (std::isfinite(ref)) {
          ASSERT_TRUE(d.touched);
          ASSERT_NEAR(d.z, ref, 1e-9) << cutter_type_name(c.type) << " at " << xy[i].transpose();
        } else {
          ASSERT_FALSE(d.touched);
          ASSERT_EQ(d.z, s.bounds().min.z());
        }
        ASSERT_EQ(many[i].z, d.z);
        ASSERT_EQ(many[i].touched, d.touched);
      }
    }
  }
}

// The index cell is a speed setting only: the drop is the highest contact over every point under the footprint
// and the sweep the deepest point along the move, whatever cells they are found in (bit for bit).
TEST(CloudSurface, IndexCellChangesNoDropAndNoSweep) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 30), h(0, 3);
  std::vector<Vec3> pts;
  for (int i = 0; i < 20000; ++i) {
    const double x = u(rng), y = u(rng);
    pts.push_back(Vec3(x, y, 2 * std::sin(x / 4) + h(rng) * 0.05));
  }
  std::vector<Vec2> xy;
  std::uniform_real_distribution<double> q(-2, 32);
  for (int i = 0; i < 400; ++i) xy.push_back(Vec2(q(rng), q(rng)));
  CloudSurfaceOptions o;
  o.detect_holes = false;
  o.sampling_radius = 0.1;
  const CloudSurface ref(pts, o);
  for (double cell : {0.15, 0.6, 2.5}) {
    o.cell = cell;
    const CloudSurface s(pts, o);
    for (const Cutter& c : {Cutter::flat(6), Cutter::ball(3), Cutter::bull(6, 1)}) {
      std::vector<Drop> a(xy.size()), b(xy.size());
      ref.drop_many(c, xy.data(), xy.size(), a.data());
      s.drop_many(c, xy.data(), xy.size(), b.data());
      for (size_t i = 0; i + 1 < xy.size(); ++i) {
        ASSERT_EQ(a[i].z, b[i].z) << "cell " << cell << " at " << xy[i].transpose();
        const Vec3 from(xy[i].x(), xy[i].y(), a[i].z - 0.3), to(xy[i + 1].x(), xy[i + 1].y(), a[i + 1].z - 0.3);
        const SweepHit ha = sweep_depth(ref, c, from, to), hb = sweep_depth(s, c, from, to);
        ASSERT_EQ(ha.depth, hb.depth) << "cell " << cell << " move " << i;
        if (ha.depth > 0) {
          ASSERT_NEAR(ha.at, hb.at, 1e-9);
        }
      }
    }
  }
}

TEST(CloudSurface, SamplingRadiusOfASquareGrid) {
  // Pitch 0.5: the nearest-neighbour spacing is the pitch; the largest empty circle has radius 0.5/sqrt 2, and
  // its 95th percentile over random positions lies a little below.
  const CloudSurface s(level_grid(40, 0.5, 3.0));
  EXPECT_NEAR(s.mean_spacing(), 0.5, 1e-9);
  EXPECT_GT(s.sampling_radius(), 0.5 * 0.5);
  EXPECT_LE(s.sampling_radius(), 0.5 / std::sqrt(2.0) + 1e-9);
  EXPECT_TRUE(s.holes().holes().empty());
}

TEST(CloudSurface, SparseCloudNeverLetsTheCutterFallBetweenPoints) {
  // Level ground at z = 5 known only every 4 mm, and a 3 mm ball: with the bare formula it falls through between
  // the points (to the floor). With the support discs (radius c) it sinks at most (g - c)²/2R-ish over an empty
  // circle of radius g: exactly R - sqrt(R² - (g - c)²); the largest here is g = 2 sqrt 2, and where g is at most
  // the sampling radius the sink is at most the allowed 0.01 mm.
  std::vector<Vec3> pts = level_grid(60, 4.0, 5.0);
  pts.push_back(Vec3(30, 30, 0.0));  // a low point: the floor
  const CloudSurface bare_s(pts, bare());
  const CloudSurface s(pts);
  const double R = 1.5, c = s.support_radius(Cutter::ball(3)), g = 2 * std::sqrt(2.0);
  EXPECT_GT(s.sampling_radius(), 0.4 * 4.0);
  EXPECT_LE(s.sampling_radius(), g + 1e-9);
  EXPECT_NEAR(c, s.sampling_radius() - std::sqrt(2 * R * 0.01), 1e-12);
  const double worst_sink = R - std::sqrt(R * R - (g - c) * (g - c));
  size_t fell = 0, checked = 0, within = 0;
  for (double x = 4; x <= 56; x += 0.37)
    for (double y = 4; y <= 56; y += 0.41) {
      if (std::hypot(x - 30, y - 30) < 8) continue;
      ++checked;
      const Drop d = s.drop(Cutter::ball(3), x, y);
      ASSERT_TRUE(d.touched);
      ASSERT_GE(d.z, 5.0 - worst_sink - 1e-9) << x << ", " << y;
      ASSERT_LE(d.z, 5.0 + 1e-9);
      within += d.z >= 5.0 - 0.01 - 1e-9;
      if (bare_s.drop(Cutter::ball(3), x, y).z < 4.0) ++fell;
    }
  EXPECT_LT(worst_sink, 0.11);  // rho is a measured 95th percentile, a little under g here
  EXPECT_GT(within, checked * 9 / 10);
  EXPECT_GT(fell, checked / 4) << "the bare formula should fall between points this sparse";
}

TEST(CloudSurface, HoleIsBridgedAtTheHighestNeighbour) {
  // A plane at z = 2 sloping to z = 3 in x, 0.25 mm pitch, with a 6 x 6 mm hole in the middle.
  std::vector<Vec3> pts;
  for (double x = 0; x <= 40; x += 0.25)
    for (double y = 0; y <= 40; y += 0.25)
      if (!(x > 17 && x < 23 && y > 17 && y < 23)) pts.push_back(Vec3(x, y, 2 + x / 40));
  const CloudSurface s(pts);
  EXPECT_NEAR(s.mean_spacing(), 0.25, 0.01);
  ASSERT_EQ(s.holes().holes().size(), 1u);
  const Hole& hole = s.holes().holes()[0];
  EXPECT_GT(hole.area, 20.0);
  EXPECT_LT(hole.area, 36.0);
  // The lid stands at the highest point around the hole: at most the rim's x = 23 + 2 cells.
  EXPECT_GE(hole.lid_z, 2 + 23.0 / 40 - 1e-9);
  EXPECT_LE(hole.lid_z, 2 + (23.0 + 2 * s.holes().grid().cell()) / 40 + 1e-9);
  // A small ball over the middle of the hole stays on the lid: it never drops into missing data.
  const Drop d = s.drop(Cutter::ball(1), 20, 20);
  EXPECT_TRUE(d.touched);
  EXPECT_NEAR(d.z, hole.lid_z, 1e-9);
  // Far from the hole: the plane.
  EXPECT_NEAR(s.drop(Cutter::ball(1), 5, 5).z, 2 + 5.0 / 40, 0.01);
  // The outside of the part is not a hole.
  EXPECT_EQ(s.holes().outside_cells(), 0u);
}

TEST(CloudSurface, LocallySparsePatchIsAHoleAndBridged) {
  // Dense level ground (0.25 mm) at z = 5 with a 12 mm patch known only every 3 mm: the patch's empty cells
  // are enclosed by data, so they are a hole under a lid, and a 3 mm ball never sinks into the patch.
  std::vector<Vec3> pts;
  for (double x = 0; x <= 40; x += 0.25)
    for (double y = 0; y <= 40; y += 0.25) {
      const bool patch = x > 14 && x < 26 && y > 14 && y < 26;
      if (!patch || (std::fmod(x, 3.0) == 0 && std::fmod(y, 3.0) == 0)) pts.push_back(Vec3(x, y, 5.0));
    }
  const CloudSurface s(pts);
  ASSERT_FALSE(s.holes().holes().empty());
  // Over the patch: the lid or the points. Where a hole cell is lidded the ball stays at 5; in a filled cell at
  // the patch's rim it is within cell * sqrt 2 of that cell's points, so it sinks at most R - sqrt(R² - (cell
  // sqrt 2)²) (the support discs are sized for the dense part and do not help there). Most positions keep the
  // sink allowed between points (0.01 mm).
  const double R = 1.5, g = std::min(R, s.holes().grid().cell() * std::sqrt(2.0));
  const double rim_sink = R - std::sqrt(R * R - g * g);
  size_t checked = 0, within = 0;
  for (double x = 14; x <= 26; x += 0.3)
    for (double y = 14; y <= 26; y += 0.3) {
      const double z = s.drop(Cutter::ball(3), x, y).z;
      ASSERT_GE(z, 5.0 - rim_sink - 1e-9) << x << ", " << y;
      ++checked;
      within += z >= 5.0 - 0.01 - 1e-9;
    }
  EXPECT_GT(within, checked * 9 / 10);
}

TEST(CloudSurface, BadInputsAreErrors) {
  EXPECT_THROW(CloudSurface(std::vector<Vec3>{}), Error);
  EXPECT_THROW(CloudSurface(std::vector<Vec3>{Vec3(0, 0, NAN)}), Error);
  CloudSurfaceOptions o;
  o.max_sink = 0;
  EXPECT_THROW(CloudSurface(std::vector<Vec3>{Vec3(0, 0, 0)}, o), Error);
  o = {};
  o.sampling_radius = -1;
  EXPECT_THROW(CloudSurface(std::vector<Vec3>{Vec3(0, 0, 0)}, o), Error);
}

namespace {

// Drops of `cutters` on a grid over the mesh, cloud against mesh within the sampling bound; counts level-ground
// checks (tight bound) and general ones.
void expect_within_sampling_bound(const std::string& name, const Mesh& mesh, double pitch, double sigma,
                                  const std::vector<Cutter>& cutters, size_t* level_checks) {
  cloudtest::Sampling sm = cloudtest::sample_mesh(mesh, pitch);
  const double eta = sigma > 0 ? cloudtest::add_noise(sm.pts, sigma) : 0.0;
  // A hole-detection cell wider than twice the plan-view covering radius (at most rho + eta) holds a sample
  // wherever the mesh is: no holes, no lids, only the points are compared here (lids: the tests above). The
  // automatic cell follows the median spacing, and samplings as anisotropic as this lattice on long thin
  // triangles (pycam-textbox.stl) get one-cell lids in their sparse bands.
  CloudSurfaceOptions so;
  so.hole_cell = 2.2 * (sm.covering + eta);
  const CloudSurface cloud(sm.pts, so);
  const MeshSurface ref(mesh);
  EXPECT_TRUE(cloud.holes().holes().empty()) << name << ": " << cloud.holes().holes().size() << " holes";
  const Box3& b = mesh.bbox;
  const double gx = (b.max.x() - b.min.x() + 8) / 37, gy = (b.max.y() - b.min.y() + 8) / 31;
  size_t compared = 0;
  for (const Cutter& c : cutters)
    for (double x = b.min.x() - 4; x <= b.max.x() + 4; x += gx)
      for (double y = b.min.y() - 4; y <= b.max.y() + 4; y += gy) {
        const Drop d = cloud.drop(c, x, y);
        const cloudtest::Bound bound = cloudtest::sampling_bound(ref, cloud, c, sm.covering, eta, x, y);
        // The grown cutter misses the mesh: the cloud's touches nothing. The eroded one touches it: the
        // cloud's touches a point.
        if (bound.misses) {
          ASSERT_FALSE(d.touched) << name << " at " << x << ", " << y;
          continue;
        }
        if (std::isfinite(bound.lo)) {
          ASSERT_TRUE(d.touched) << name << " at " << x << ", " << y;
        }
        if (!d.touched) continue;
        ASSERT_GE(d.z, bound.lo - 1e-9) << name << " " << cutter_type_name(c.type) << " at " << x << ", " << y;
        ASSERT_LE(d.z, bound.hi + 1e-9) << name << " " << cutter_type_name(c.type) << " at " << x << ", " << y;
        ++compared;
        cloudtest::Bound level;
        if (cloudtest::level_ground(ref, cloud, c, sm.covering, eta, x, y, level)) {
          ASSERT_GE(d.z, level.lo - 1e-9) << name << " level ground at " << x << ", " << y;
          ASSERT_LE(d.z, level.hi + 1e-9) << name << " level ground at " << x << ", " << y;
          ++*level_checks;
        }
      }
  EXPECT_GT(compared, 500u) << name;
}

}  // namespace

TEST(CloudSurface, PrimitiveCloudsWithinTheSamplingBoundOfTheMeshDropCutter) {
  // Uniform samplings of the seed primitives (0.6 mm lattice), clean and with Gaussian noise sigma = 0.02 mm.
  size_t level = 0;
  for (const std::string& name : primitive_names())
    for (double sigma : {0.0, 0.02})
      expect_within_sampling_bound(name + (sigma > 0 ? " noisy" : ""), make_primitive(name), 0.6, sigma,
                                   {Cutter::ball(3), Cutter::ball(5), Cutter::flat(10)}, &level);
  EXPECT_GT(level, 200u);  // cube, cylinder and cavity tops are level ground
}

TEST(CloudSurface, RealModelCloudsWithinTheSamplingBoundOfTheMeshDropCutter) {
  size_t level = 0;
  for (const char* file : {"failedinpycam.stl", "pycam-textbox.stl", "mount_rush.stl"})
    for (double sigma : {0.0, 0.02})
      expect_within_sampling_bound(std::string(file) + (sigma > 0 ? " noisy" : ""),
                                   read_stl(std::string(ROSMILL_TEST_DATA "/") + file), 0.5, sigma,
                                   {Cutter::ball(3), Cutter::flat(10)}, &level);
  EXPECT_GT(level, 50u);
}

TEST(CloudSurface, EngineStrategiesRunOnACloud) {
  // raster, waterline, rough and grid-rough through the Surface seam on a sampled dome: each gives cutting moves, and
  // no
  // cutter location puts the cutter into a point.
  const Mesh dome = make_primitive("dome");
  PointCloud cloud;
  cloud.points = cloudtest::sample_mesh(dome, 1.0).pts;
  cloud.recompute_bbox();
  const cloudtest::SortedPoints brute(cloud.points);
  PlanParams p;
  p.tool.cutter = Cutter::ball(6);
  p.tool.stepover = 4;
  p.tool.stepdown = 10;
  p.tolerance = 0.05;
  PlanningRequest r;
  r.input.cloud = &cloud;
  r.params = p;
  for (const char* strategy : {"raster", "waterline", "rough", "grid-rough"}) {
    r.strategy = strategy;
    const Job job = plan(r);
    ASSERT_EQ(job.size(), 1u) << strategy;
    const std::vector<Vec3> cl = cloudtest::feed_locations(job[0]);
    EXPECT_GT(cl.size(), 50u) << strategy;
    for (size_t i = 0; i < cl.size(); i += 7)
      ASSERT_LE(brute.penetration(p.tool.cutter, cl[i]), p.tolerance + 1e-9) << strategy << " at " << cl[i].transpose();
  }
}
