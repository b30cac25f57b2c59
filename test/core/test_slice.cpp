// Slicing: the seed primitives against their analytic sections, degenerate planes, open and non-manifold meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/slice/slicer.hpp"
#include "test_slice_meshes.hpp"

using namespace rosmill::core;
using slice_test::box_corners;
using slice_test::outward;

namespace {

double radius_of(const Vec2& p) { return p.norm(); }

// The layer's only contour, asserted to be one closed outer contour.
const Contour& only_outer(const SliceLayer& l) {
  EXPECT_EQ(l.contours.size(), 1u) << "z = " << l.z;
  const Contour& c = l.contours.at(0);
  EXPECT_TRUE(c.closed);
  EXPECT_FALSE(c.hole);
  EXPECT_EQ(c.parent, -1);
  EXPECT_GT(signed_area(c.points), 0.0) << "outer contours run counter-clockwise";
  return c;
}

}  // namespace

TEST(Slice, CubeIsOneSquareAtEveryLevelIncludingZminAndZmax) {
  const Mesh cube = make_primitive("cube");
  std::vector<double> z = planes_by_step(cube, 7.5);
  ASSERT_EQ(z.size(), 8u);
  EXPECT_EQ(z.back(), 60.0);
  z.insert(z.begin(), 0.0);
  const auto layers = slice_mesh(cube, z);
  for (const SliceLayer& l : layers) {
    const Contour& c = only_outer(l);
    EXPECT_EQ(c.area, 3600.0) << "z = " << l.z;
    for (const Vec2& p : c.points) {
      EXPECT_TRUE(p.x() == 0 || p.x() == 60 || p.y() == 0 || p.y() == 60);
      EXPECT_TRUE(p.x() >= 0 && p.x() <= 60 && p.y() >= 0 && p.y() <= 60);
    }
    EXPECT_EQ(l.flat_area, (l.z == 0.0 || l.z == 60.0) ? 3600.0 : 0.0) << "z = " << l.z;
  }
}

TEST(Slice, CylinderIsThe36GonOfRadius25) {
  const Mesh m = make_primitive("cylinder");
  const double polygon = 0.5 * 36 * 25 * 25 * std::sin(2 * M_PI / 36);
  for (const SliceLayer& l : slice_mesh(m, planes_by_count(m, 9))) {
    const Contour& c = only_outer(l);
    EXPECT_NEAR(c.area, polygon, 1e-9);
    EXPECT_LT(c.area, M_PI * 625);
    EXPECT_GT(c.area, M_PI * 625 * std::cos(M_PI / 36) * std::cos(M_PI / 36));
    EXPECT_EQ(c.points.size(), 72u);  // 36 vertical edges and 36 quad diagonals
    for (const Vec2& p : c.points) EXPECT_LE(radius_of(p), 25.0 + 1e-12);
  }
}

TEST(Slice, ConeRadiusIs25TimesOneMinusZOver60) {
  const Mesh m = make_primitive("cone");
  const auto layers = slice_mesh(m, planes_by_step(m, 5.0));
  ASSERT_EQ(layers.size(), 12u);
  for (const SliceLayer& l : layers) {
    if (l.z == 60.0) {
      EXPECT_TRUE(l.contours.empty()) << "the section through the apex is a point, not a contour";
      continue;
    }
    const Contour& c = only_outer(l);
    EXPECT_EQ(c.points.size(), 36u);
    for (const Vec2& p : c.points) EXPECT_NEAR(radius_of(p), 25.0 * (1 - l.z / 60.0), 1e-9);
  }
}

TEST(Slice, DomeRadiusIsSqrtOf50SquaredMinusZSquared) {
  const Mesh m = make_primitive("dome");
  const auto layers = slice_mesh(m, planes_by_step(m, 2.5));
  ASSERT_EQ(layers.size(), 20u);
  for (const SliceLayer& l : layers) {
    if (l.z == 50.0) {
      EXPECT_TRUE(l.contours.empty());
      continue;
    }
    const Contour& c = only_outer(l);
    const double r = std::sqrt(50.0 * 50.0 - l.z * l.z);
    // The facets are chords of the sphere: every point is inside it and within the chord height below it.
    for (const Vec2& p : c.points) {
      EXPECT_LE(std::hypot(radius_of(p), l.z), 50.0 + 1e-9);
      EXPECT_GE(std::hypot(radius_of(p), l.z), 50.0 * std::cos(M_PI / 30) * std::cos(M_PI / 60) - 1e-9);
    }
    EXPECT_NEAR(c.area, M_PI * r * r, 0.03 * M_PI * r * r + 5.0);
  }
}

TEST(Slice, CavityHasAHoleInsideTheBlockOutline) {
  const Mesh m = make_primitive("cavity");
  const auto layers = slice_mesh(m, {5.0, 30.0, 59.0});
  only_outer(layers[0]);
  for (size_t k = 1; k < 3; ++k) {
    const SliceLayer& l = layers[k];
    ASSERT_EQ(l.contours.size(), 2u);
    const int outer = l.contours[0].hole ? 1 : 0, hole = 1 - outer;
    const Contour& o = l.contours[size_t(outer)];
    const Contour& h = l.contours[size_t(hole)];
    EXPECT_TRUE(o.closed && h.closed);
    EXPECT_FALSE(o.hole);
    EXPECT_TRUE(h.hole);
    EXPECT_EQ(h.parent, outer);
    EXPECT_EQ(o.parent, -1);
    EXPECT_GT(signed_area(o.points), 0.0);
    EXPECT_LT(signed_area(h.points), 0.0) << "holes run clockwise";
    const double r = std::sqrt(50.0 * 50.0 - (60.0 - l.z) * (60.0 - l.z));
    for (const Vec2& p : h.points) {
      EXPECT_LE(radius_of(p), r + 1e-9);
      EXPECT_GE(radius_of(p), r * 0.97 - 0.2);
    }
    for (const Vec2& p : o.points) EXPECT_LE(radius_of(p), 60.0 + 1e-9);
  }
}

TEST(Slice, PlaneThroughARingOfVerticesGivesTheRing) {
  const Mesh m = make_primitive("dome");
  // The dome's rings are at 50 cos(polar): pick a ring height from the mesh itself.
  double ring_z = 0;
  for (const Vec3& v : m.vertices)
    if (v.z() > 20 && v.z() < 30) ring_z = v.z();
  ASSERT_GT(ring_z, 0.0);
  const auto layers = slice_mesh(m, {ring_z});
  const Contour& c = only_outer(layers[0]);
  EXPECT_EQ(c.points.size(), 30u) << "exactly the 30 ring vertices";
  for (const Vec2& p : c.points) {
    bool is_vertex = false;
    for (const Vec3& v : m.vertices) is_vertex |= v.z() == ring_z && v.x() == p.x() && v.y() == p.y();
    EXPECT_TRUE(is_vertex);
  }
}

TEST(Slice, OctahedronThroughItsEquatorAndApexes) {
  const Vec3 px(1, 0, 0), nx(-1, 0, 0), py(0, 1, 0), ny(0, -1, 0), pz(0, 0, 1), nz(0, 0, -1);
  std::vector<Vec3> c;
  const Vec3 ring[4] = {px, py, nx, ny};
  for (int i = 0; i < 4; ++i) {
    slice_test::tri(c, ring[i], ring[(i + 1) % 4], pz);
    slice_test::tri(c, ring[(i + 1) % 4], ring[i], nz);
  }
  const Mesh m = outward(c);
  const auto layers = slice_mesh(m, {-1.0, 0.0, 0.5, 1.0});
  EXPECT_TRUE(layers[0].contours.empty()) << "Zmin is an apex";
  EXPECT_EQ(only_outer(layers[1]).points.size(), 4u);
  EXPECT_DOUBLE_EQ(only_outer(layers[1]).area, 2.0);
  EXPECT_DOUBLE_EQ(only_outer(layers[2]).area, 0.5);
  EXPECT_TRUE(layers[3].contours.empty());
}

TEST(Slice, PlaneThroughAFlatStepReportsTheFlatRegion) {
  const Mesh m = slice_test::step_block();
  ASSERT_TRUE(m.closed());
  const auto layers = slice_mesh(m, {15.0, 30.0, 45.0, 60.0});
  EXPECT_DOUBLE_EQ(only_outer(layers[0]).area, 3600.0);
  // At the step the section is the limit from below (the full block) and the step's top is the flat region.
  EXPECT_DOUBLE_EQ(only_outer(layers[1]).area, 3600.0);
  EXPECT_DOUBLE_EQ(layers[1].flat_area, 1800.0);
  EXPECT_DOUBLE_EQ(only_outer(layers[2]).area, 1800.0);
  EXPECT_DOUBLE_EQ(layers[2].flat_area, 0.0);
  EXPECT_DOUBLE_EQ(only_outer(layers[3]).area, 1800.0);
  EXPECT_DOUBLE_EQ(layers[3].flat_area, 1800.0);
}

TEST(Slice, BoxWithAHoleThroughItNestsTheHole) {
  // A 60 mm square tube (a square ring prism): outer wall, inner wall, ring-shaped top and bottom.
  std::vector<Vec3> c;
  const double o[4][2] = {{0, 0}, {60, 0}, {60, 60}, {0, 60}}, in[4][2] = {{20, 20}, {40, 20}, {40, 40}, {20, 40}};
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    for (double z : {0.0, 10.0}) {
      const bool up = z > 0;
      const Vec3 a(o[i][0], o[i][1], z), b(o[j][0], o[j][1], z), d(in[i][0], in[i][1], z), e(in[j][0], in[j][1], z);
      if (up) {
        slice_test::tri(c, a, b, e);
        slice_test::tri(c, a, e, d);
      } else {
        slice_test::tri(c, a, e, b);
        slice_test::tri(c, a, d, e);
      }
    }
    const Vec3 a(o[i][0], o[i][1], 0), b(o[j][0], o[j][1], 0), a1(o[i][0], o[i][1], 10), b1(o[j][0], o[j][1], 10);
    slice_test::tri(c, a, b, b1);
    slice_test::tri(c, a, b1, a1);
    const Vec3 d(in[i][0], in[i][1], 0), e(in[j][0], in[j][1], 0), d1(in[i][0], in[i][1], 10), e1(in[j][0], in[j][1], 10);
    slice_test::tri(c, d, e1, e);
    slice_test::tri(c, d, d1, e1);
  }
  const Mesh m = outward(c);
  ASSERT_TRUE(m.closed());
  const auto layers = slice_mesh(m, {0.0, 5.0, 10.0});
  for (const SliceLayer& l : layers) {
    ASSERT_EQ(l.contours.size(), 2u) << "z = " << l.z;
    const int hole = l.contours[0].hole ? 0 : 1;
    EXPECT_TRUE(l.contours[size_t(hole)].hole);
    EXPECT_FALSE(l.contours[size_t(1 - hole)].hole);
    EXPECT_EQ(l.contours[size_t(hole)].parent, 1 - hole);
    EXPECT_DOUBLE_EQ(l.contours[size_t(hole)].area, 400.0);
    EXPECT_DOUBLE_EQ(l.contours[size_t(1 - hole)].area, 3600.0);
    EXPECT_LT(signed_area(l.contours[size_t(hole)].points), 0.0);
  }
  EXPECT_DOUBLE_EQ(layers[0].flat_area, 3200.0);
  EXPECT_DOUBLE_EQ(layers[1].flat_area, 0.0);
  EXPECT_DOUBLE_EQ(layers[2].flat_area, 3200.0);
}

TEST(Slice, OpenMeshGivesAnOpenChainReportedAsOpen) {
  std::vector<Vec3> cube = cube_corners(60.0);
  cube.erase(cube.begin() + 3 * 6, cube.begin() + 3 * 8);  // the +X side
  const Mesh m = build_mesh(cube);
  ASSERT_FALSE(m.closed());
  const auto layers = slice_mesh(m, {30.0});
  ASSERT_EQ(layers[0].contours.size(), 1u);
  const Contour& c = layers[0].contours[0];
  EXPECT_FALSE(c.closed);
  EXPECT_EQ(c.points.size(), 7u);  // 4 vertical edges and 3 diagonals
  EXPECT_EQ(c.points.front().x(), 60.0);
  EXPECT_EQ(c.points.back().x(), 60.0);
  EXPECT_EQ(c.area, 0.0);
  const SliceSummary s = summarize(layers);
  EXPECT_EQ(s.open_contours, 1u);
  EXPECT_EQ(s.contours, 1u);
  EXPECT_EQ(s.points, 7u);
}

TEST(Slice, CubesTouchingAlongAnEdgeGiveTwoClosedSquares) {
  std::vector<Vec3> c = box_corners({0, 0, 0}, {1, 1, 1});
  const std::vector<Vec3> b = box_corners({1, 1, 0}, {2, 2, 1});
  c.insert(c.end(), b.begin(), b.end());
  const Mesh m = build_mesh(c);
  size_t nonmanifold = 0;
  for (const MeshEdge& e : m.edges) nonmanifold += e.nonmanifold();
  ASSERT_EQ(nonmanifold, 1u);
  const auto layers = slice_mesh(m, {0.5});
  ASSERT_EQ(layers[0].contours.size(), 2u);
  for (const Contour& k : layers[0].contours) {
    EXPECT_TRUE(k.closed);
    EXPECT_FALSE(k.hole);
    EXPECT_DOUBLE_EQ(k.area, 1.0);
    EXPECT_EQ(k.points.size(), 8u);
  }
}

TEST(Slice, LayersComeBackInTheCallersOrder) {
  const Mesh m = make_primitive("cone");
  const auto layers = slice_mesh(m, {30.0, 10.0, 50.0});
  EXPECT_EQ(layers[0].z, 30.0);
  EXPECT_EQ(layers[1].z, 10.0);
  EXPECT_NEAR(layers[1].contours.at(0).points[0].norm(), 25.0 * (1 - 10.0 / 60), 1e-9);
  EXPECT_NEAR(layers[2].contours.at(0).points[0].norm(), 25.0 * (1 - 50.0 / 60), 1e-9);
}

TEST(Slice, PlaneChoices) {
  const Mesh m = make_primitive("cube");
  EXPECT_EQ(planes_by_step(m, 0.1).size(), 600u);
  EXPECT_EQ(planes_by_step(m, 0.1).back(), 60.0);
  const auto n = planes_by_count(m, 5);
  ASSERT_EQ(n.size(), 5u);
  EXPECT_DOUBLE_EQ(n[0], 10.0);
  EXPECT_DOUBLE_EQ(n[4], 50.0);
  const auto a = planes_by_accuracy(m, 7.0);
  ASSERT_EQ(a.size(), 10u);  // 9 intervals of 6.67 mm
  EXPECT_EQ(a.front(), 0.0);
  EXPECT_EQ(a.back(), 60.0);
  EXPECT_THROW(planes_by_step(m, 0.0), Error);
  EXPECT_THROW(planes_by_step(m, NAN), Error);
  EXPECT_THROW(planes_by_count(m, 0), Error);
  EXPECT_THROW(planes_from_list({1.0, INFINITY}), Error);
  EXPECT_EQ(planes_from_list({3, 1, 2}), (std::vector<double>{1, 2, 3}));
}

TEST(Slice, DatExportHasOneBlockPerContour) {
  const Mesh m = make_primitive("cavity");
  const auto layers = slice_mesh(m, {5.0, 30.0});
  const std::string path = ::testing::TempDir() + "slice_test.dat";
  write_slices_dat(path, layers);
  std::ifstream in(path);
  std::string line;
  size_t blocks = 1, rows = 0;
  while (std::getline(in, line)) {
    if (line.empty()) {
      ++blocks;
      continue;
    }
    double x, y, z;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf %lf", &x, &y, &z), 3) << line;
    EXPECT_TRUE(z == 5.0 || z == 30.0);
    ++rows;
  }
  EXPECT_EQ(blocks, 3u);
  EXPECT_EQ(rows, summarize(layers).points + 3);  // each closed contour repeats its first point
  EXPECT_THROW(write_slices_dat("/nonexistent/dir/x.dat", layers), Error);
}

TEST(Slice, WavyHeightFieldIsClosedAndNestedAtEveryPlane) {
  const Mesh m = slice_test::wavy_solid(120, 200.0);
  ASSERT_TRUE(m.closed());
  EXPECT_EQ(m.bbox.max.z(), 17.5);
  const auto layers = slice_mesh(m, planes_by_step(m, 0.5));
  ASSERT_EQ(layers.size(), 35u);
  for (const SliceLayer& l : layers) {
    double net = 0.0;
    for (const Contour& c : l.contours) {
      EXPECT_TRUE(c.closed) << "z = " << l.z;
      net += c.hole ? -c.area : c.area;
      EXPECT_EQ(signed_area(c.points) > 0, !c.hole);
    }
    // Below the lowest valley (2.5) the section is the whole 200 x 200 square.
    if (l.z < 2.5) {
      EXPECT_NEAR(net, 40000.0, 1e-6) << "z = " << l.z;
    }
    EXPECT_LE(net, 40000.0 + 1e-6);
  }
}
