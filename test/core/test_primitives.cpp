// The seed primitives: the paper's triangle counts, closed and consistently oriented, volumes within the
// faceting error of the analytic solid (bounds computed here from the faceting itself).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/primitives.hpp"

using namespace rosmill::core;

namespace {

// Smallest distance from `centre` to the plane of any face whose vertices all lie on the sphere of radius r
// about `centre`: the inscribed radius of the faceted sphere part.
double inscribed_radius(const Mesh& m, const Vec3& centre, double r) {
  double rin = r;
  for (size_t f = 0; f < m.face_count(); ++f) {
    bool on_sphere = true;
    for (int i = 0; i < 3; ++i) on_sphere &= std::abs((m.corner(f, i) - centre).norm() - r) < 1e-9;
    if (on_sphere) rin = std::min(rin, std::abs((m.corner(f, 0) - centre).dot(m.normals[f])));
  }
  return rin;
}

double polygon_area(int n, double r) { return 0.5 * n * r * r * std::sin(2 * M_PI / n); }

void expect_clean(const MeshReport& r, size_t triangles) {
  EXPECT_EQ(r.triangles, triangles);
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.open_edges, 0u);
  EXPECT_EQ(r.nonmanifold_edges, 0u);
  EXPECT_EQ(r.inconsistent_edges, 0u);
  EXPECT_EQ(r.degenerate, 0u);
  EXPECT_GT(r.volume, 0.0) << "normals must point outwards";
}

}  // namespace

TEST(Primitives, CubeIsExact) {
  MeshReport r = report(make_primitive("cube"));
  expect_clean(r, 12);
  EXPECT_EQ(r.vertices, 8u);
  EXPECT_DOUBLE_EQ(r.volume, 216000.0);
  EXPECT_DOUBLE_EQ(r.area, 6 * 3600.0);
}

TEST(Primitives, CylinderIsA36GonPrism) {
  MeshReport r = report(make_primitive("cylinder"));
  expect_clean(r, 144);
  EXPECT_NEAR(r.volume, polygon_area(36, 25) * 60, 1e-6);
  EXPECT_LT(r.volume, M_PI * 25 * 25 * 60);
  EXPECT_NEAR(r.bbox.max.z(), 60.0, 0);
}

TEST(Primitives, ConeIsA36GonPyramid) {
  MeshReport r = report(make_primitive("cone"));
  expect_clean(r, 72);
  EXPECT_NEAR(r.volume, polygon_area(36, 25) * 60 / 3, 1e-6);
}

TEST(Primitives, DomeVolumeWithinFaceting) {
  Mesh m = make_primitive("dome");
  MeshReport r = report(m);
  expect_clean(r, 900);
  const double rin = inscribed_radius(m, Vec3::Zero(), 50);
  EXPECT_LT(rin, 50.0);
  EXPECT_GT(r.volume, 2.0 / 3 * M_PI * std::pow(rin, 3));
  EXPECT_LT(r.volume, 2.0 / 3 * M_PI * std::pow(50.0, 3));
  EXPECT_DOUBLE_EQ(r.bbox.min.z(), 0.0);
  EXPECT_NEAR(r.bbox.max.z(), 50.0, 1e-12);
}

TEST(Primitives, CavityIsABlockMinusAHemisphere) {
  Mesh m = make_primitive("cavity");
  MeshReport r = report(m);
  expect_clean(r, 900);
  const double block = polygon_area(30, 60) * 60;
  const double rin = inscribed_radius(m, Vec3(0, 0, 60), 50);
  EXPECT_GT(r.volume, block - 2.0 / 3 * M_PI * std::pow(50.0, 3));
  EXPECT_LT(r.volume, block - 2.0 / 3 * M_PI * std::pow(rin, 3));
  EXPECT_DOUBLE_EQ(r.bbox.max.z(), 60.0);
  EXPECT_DOUBLE_EQ(r.bbox.min.z(), 0.0);
}

TEST(Primitives, UnknownNameIsAnError) { EXPECT_THROW(make_primitive("torus"), std::runtime_error); }
