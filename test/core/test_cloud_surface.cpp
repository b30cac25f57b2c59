// CloudSurface: the drop-cutter against points (seed 004) for flat, ball and bull cutters, its grid index
// against brute force, lids over holes, and clouds sampled from the seed primitives against the exact mesh
// drop-cutter.
#include <gtest/gtest.h>

#include <random>

#include "rosmill/cloud/cloud_surface.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "test_cloud_support.hpp"

using namespace rosmill;

namespace {

double brute_drop(const std::vector<Vec3>& pts, const Cutter& c, double x, double y) {
  // The lowest tip with penetration <= 0: the highest z_p - (underside height above tip) over the footprint.
  const Vec3 tip0(x, y, 0.0);
  const double pen = cloudtest::penetration(pts, c, tip0, 0.0);
  return pen;  // tip 0 penetrates by `pen`, so the touching tip is at +pen
}

}  // namespace

TEST(CloudSurface, SinglePointFormulas) {
  const std::vector<Vec3> pts = {Vec3(0, 0, 10)};
  CloudSurfaceOptions o;
  o.detect_holes = false;
  const CloudSurface s(pts, o);
  // Ball R = 3 at d = 2: z_p + sqrt(R² - d²) - R.
  EXPECT_NEAR(s.drop(Cutter::ball(6), 2, 0).z, 10 + std::sqrt(9.0 - 4.0) - 3, 1e-12);
  EXPECT_NEAR(s.drop(Cutter::ball(6), 0, 0).z, 10, 1e-12);
  // Flat: z_p anywhere under the footprint, nothing outside.
  EXPECT_NEAR(s.drop(Cutter::flat(6), 2.9, 0).z, 10, 1e-12);
  EXPECT_TRUE(s.drop(Cutter::flat(6), 2.9, 0).touched);
  EXPECT_FALSE(s.drop(Cutter::flat(6), 3.1, 0).touched);
  // Bull D 6 r 1: flat inside Rf = 2, torus beyond: z_p - r + sqrt(r² - (d - Rf)²).
  EXPECT_NEAR(s.drop(Cutter::bull(6, 1), 1.9, 0).z, 10, 1e-12);
  EXPECT_NEAR(s.drop(Cutter::bull(6, 1), 2.5, 0).z, 10 - 1 + std::sqrt(1 - 0.25), 1e-12);
  EXPECT_NEAR(s.drop(Cutter::bull(6, 1), 0, 2.5).z, 10 - 1 + std::sqrt(1 - 0.25), 1e-12);
}

TEST(CloudSurface, GridIndexMatchesBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 50), h(0, 8);
  std::vector<Vec3> pts;
  for (int i = 0; i < 20000; ++i) pts.push_back(Vec3(u(rng), u(rng), h(rng) + 0.1 * u(rng)));
  CloudSurfaceOptions o;
  o.detect_holes = false;
  const CloudSurface s(pts, o);
  std::vector<Vec2> xy;
  std::uniform_real_distribution<double> q(-5, 55);
  for (int i = 0; i < 300; ++i) xy.push_back(Vec2(q(rng), q(rng)));
  for (const Cutter& c : {Cutter::flat(10), Cutter::ball(5), Cutter::bull(8, 2), Cutter::ball(0.5)}) {
    std::vector<Drop> many(xy.size());
    s.drop_many(c, xy.data(), xy.size(), many.data());
    for (size_t i = 0; i < xy.size(); ++i) {
      const double ref = brute_drop(pts, c, xy[i].x(), xy[i].y());
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

TEST(CloudSurface, PrimitiveCloudsMatchTheMeshDropCutter) {
  // Bound: the points lie on the mesh, so the cloud's drop is never above the mesh's. Below it by at most the
  // sampling error: a sample lies within rho of the contact point, and a sphere tangent there rises from the
  // surface by rho²/(2R) along the normal, i.e. rho²/(2R cos θ) vertically (θ: contact normal vs +Z). Contacts
  // steeper than 70° are left out of the comparison (the bound grows without limit; the gouge tests cover them).
  const double rho = 0.5, R = 1.5;
  for (const std::string name : {"dome", "cavity", "cone", "cube", "cylinder"}) {
    const Mesh mesh = make_primitive(name);
    const std::vector<Vec3> pts = cloudtest::sample_mesh(mesh, rho);
    const CloudSurface s(pts);
    EXPECT_TRUE(s.holes().holes().empty()) << name << ": " << s.holes().holes().size() << " holes, cell "
                                           << s.holes().grid().cell();
    size_t compared = 0;
    for (double x = mesh.bbox.min.x() - 1; x <= mesh.bbox.max.x() + 1; x += 3.7)
      for (double y = mesh.bbox.min.y() - 1; y <= mesh.bbox.max.y() + 1; y += 3.1) {
        double cos_t = 1;
        const double ref = cloudtest::mesh_ball_drop(mesh, R, x, y, &cos_t);
        const Drop d = s.drop(Cutter::ball(2 * R), x, y);
        if (!std::isfinite(ref)) continue;
        ASSERT_LE(d.z, ref + 1e-9) << name << " at " << x << ", " << y;
        if (cos_t < std::cos(70 * M_PI / 180)) continue;
        ASSERT_GE(d.z, ref - rho * rho / (2 * R * cos_t) - 1e-9) << name << " at " << x << ", " << y;
        ++compared;
      }
    EXPECT_GT(compared, 150u) << name;
  }
}
