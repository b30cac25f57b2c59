// Drop-cutter: each contact type against analytic answers, the bull-nose edge against a 1-D brute-force search,
// whole triangles against dense sampling, and the indexed surface against the independent all-triangles
// reference (cutter/reference_drop: a concave maximisation that shares no code with the contact kernels) on the
// seed primitives and on real models.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rosmill/cutter/contact.hpp"
#include "rosmill/testing/reference_drop.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/plan/mesh_surface.hpp"

using namespace rosmill::core;

namespace {

Mesh one_triangle(const Vec3& a, const Vec3& b, const Vec3& c) { return build_mesh({a, b, c}); }

// max over the chord of the footprint of p.z - h(d) along an edge, by ternary search (the function is concave).
double edge_reference(const Cutter& cutter, double x, double y, const Vec3& P, const Vec3& Q) {
  const CutterProfile cp(cutter);
  auto f = [&](double t) {
    const Vec3 p = P + t * (Q - P);
    const double d = std::hypot(p.x() - x, p.y() - y);
    return d > cp.R ? kNoContact : p.z() - cp.height(d);
  };
  // Feasible interval: where the edge is under the footprint.
  const int n = 20000;
  double lo = -1, hi = -1;
  for (int i = 0; i <= n; ++i) {
    const double t = double(i) / n;
    if (f(t) > kNoContact) {
      if (lo < 0) lo = t;
      hi = t;
    }
  }
  if (lo < 0) return kNoContact;
  // Widen to the exact chord ends by bisection on feasibility.
  auto widen = [&](double in, double out) {
    for (int k = 0; k < 80; ++k) {
      const double mid = 0.5 * (in + out);
      (f(mid) > kNoContact ? in : out) = mid;
    }
    return in;
  };
  lo = widen(lo, std::max(0.0, lo - 1.0 / n));
  hi = widen(hi, std::min(1.0, hi + 1.0 / n));
  for (int k = 0; k < 200; ++k) {
    const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
    (f(a) < f(b) ? lo : hi) = (f(a) < f(b) ? a : b);
  }
  return f(0.5 * (lo + hi));
}

}  // namespace

TEST(DropCutter, BallOnPlaneAndOverCubeEdge) {
  const MeshSurface s(make_primitive("cube"));
  const Cutter ball = Cutter::ball(6);
  EXPECT_NEAR(s.drop(ball, 30, 30).z, 60.0, 1e-12);
  // Axis 2 mm outside the top edge x = 60: the ball's circle of radius 3 rests on the edge.
  EXPECT_NEAR(s.drop(ball, 62, 30).z, 57.0 + std::sqrt(5.0), 1e-12);
  EXPECT_FALSE(s.drop(ball, 63.5, 30).touched);
  EXPECT_EQ(s.drop(ball, 63.5, 30).z, 0.0);
}

TEST(DropCutter, FlatOnEdgeAndTiltedPlane) {
  const MeshSurface s(make_primitive("cube"));
  const Cutter flat = Cutter::flat(10);
  EXPECT_NEAR(s.drop(flat, 64.9, 10).z, 60.0, 1e-12);
  EXPECT_FALSE(s.drop(flat, 65.1, 10).touched);
  // A plane z = 0.5 x: the flat cutter rests on its rim's highest point, x + R.
  const MeshSurface ramp(build_mesh({Vec3(-50, -50, -25), Vec3(50, -50, 25), Vec3(50, 50, 25), Vec3(-50, -50, -25),
                                     Vec3(50, 50, 25), Vec3(-50, 50, -25)}));
  EXPECT_NEAR(ramp.drop(flat, 3, 4).z, 0.5 * (3 + 5), 1e-12);
  // Ball on the same plane: the tip sits R (1/cos - 1) below the contact-free height of the centre.
  const double slope = 0.5, R = 3;
  EXPECT_NEAR(ramp.drop(Cutter::ball(6), 3, 4).z, 0.5 * 3 + R * std::sqrt(1 + slope * slope) - R, 1e-12);
  // Bull nose D10 r2: the torus' tube centre circle radius 3 offsets along the slope, then the ball part.
  const double R1 = 3, r = 2, nz = 1 / std::sqrt(1 + slope * slope);
  EXPECT_NEAR(ramp.drop(Cutter::bull(10, 2), 3, 4).z, 0.5 * (3 + R1) + r / nz - r, 1e-12);
}

TEST(DropCutter, BullOnVertex) {
  const MeshSurface s(make_primitive("cube"));
  const Cutter bull = Cutter::bull(10, 2);
  // Axis diagonal from the corner (60, 60, 60) at distance d = 4.2: on the torus, h = r - sqrt(r^2 - (d - R1)^2).
  const double d = 4.2, e = d - 3.0;
  const Drop drop = s.drop(bull, 60 + d / std::sqrt(2.0), 60 + d / std::sqrt(2.0));
  EXPECT_TRUE(drop.touched);
  EXPECT_NEAR(drop.z, 60.0 - (2.0 - std::sqrt(4.0 - e * e)), 1e-12);
  // Inside the flat bottom's radius the corner carries the cutter at its own height.
  EXPECT_NEAR(s.drop(bull, 62, 61).z, 60.0, 1e-12);
}

TEST(DropCutter, BallOnDomeMatchesSphere) {
  const MeshSurface s(make_primitive("dome"));
  const double R = 50, r = 3;
  EXPECT_NEAR(s.drop(Cutter::ball(6), 0, 0).z, 50.0, 1e-9);  // the pole is a vertex
  // Facets are inscribed in the sphere: the drop lies between the spheres of radius R and R - sag.
  const double sag = R * (1 - std::cos(M_PI / 30)) + 1e-9;
  for (double x = -45; x <= 45; x += 7.5) {
    const double on_sphere = std::sqrt((R + r) * (R + r) - x * x * 0.5 - x * x * 0.25) - r;
    const double below = std::sqrt((R - sag + r) * (R - sag + r) - x * x * 0.75) - r;
    const double z = s.drop(Cutter::ball(6), x * std::sqrt(0.5), x * 0.5).z;
    EXPECT_LE(z, on_sphere + 1e-9) << x;
    EXPECT_GE(z, below - 1e-9) << x;
  }
}

TEST(DropCutter, EdgeContactsMatchOneDimensionalSearch) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-5, 5);
  const Cutter cutters[] = {Cutter::flat(6), Cutter::ball(6), Cutter::bull(6, 1), Cutter::bull(8, 3.5),
                            Cutter::bull(6, 0.2)};
  int compared = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 P(u(rng), u(rng), u(rng)), Q(u(rng), u(rng), u(rng));
    const double x = u(rng) * 0.6, y = u(rng) * 0.6;
    for (const Cutter& c : cutters) {
      const CutterProfile cp(c);
      double exact = std::max({edge_contact(cp, x, y, P.data(), Q.data()), vertex_contact(cp, x, y, P.data()),
                               vertex_contact(cp, x, y, Q.data())});
      const double ref = edge_reference(c, x, y, P, Q);
      if (ref == kNoContact) {
        EXPECT_EQ(exact, kNoContact);
        continue;
      }
      ASSERT_NEAR(exact, ref, 1e-7) << cutter_type_name(c.type) << " trial " << trial;
      ++compared;
    }
    if (trial == 300) break;  // keeps the suite fast; 300 x 5 edges are plenty
  }
  EXPECT_GT(compared, 500);
}

TEST(DropCutter, TrianglesNeverPenetratedAndTouchedAtDenseSamples) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-4, 4);
  const Cutter cutters[] = {Cutter::flat(6), Cutter::ball(6), Cutter::bull(6, 1.5)};
  for (int trial = 0; trial < 60; ++trial) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const MeshSurface s(one_triangle(a, b, c));
    const double x = u(rng) * 0.5, y = u(rng) * 0.5;
    for (const Cutter& cut : cutters) {
      const CutterProfile cp(cut);
      const Drop d = s.drop(cut, x, y);
      double sampled = kNoContact;
      const int n = 300;
      for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j) {
          const Vec3 p = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
          const double dist = std::hypot(p.x() - x, p.y() - y);
          if (dist <= cp.R) sampled = std::max(sampled, p.z() - cp.height(dist));
        }
      if (sampled == kNoContact) continue;
      ASSERT_TRUE(d.touched);
      EXPECT_GE(d.z, sampled - 1e-9) << "cutter goes into the triangle, trial " << trial;
      EXPECT_LE(d.z, sampled + 0.05) << "cutter floats above the triangle, trial " << trial;
      // The reference obeys the same bounds (so it is checked by something other than the code it checks).
      const double ref = reference_triangle_drop(cut, x, y, a, b, c);
      EXPECT_GE(ref, sampled - 1e-9) << "reference, trial " << trial;
      EXPECT_LE(ref, sampled + 0.05) << "reference, trial " << trial;
    }
  }
}

// Random axis positions over the model's box grown by the cutter, the indexed drops against the reference.
void expect_equal_to_reference(const Mesh& mesh, const Cutter& c, int points, unsigned seed, const char* name) {
  const MeshSurface s(mesh);
  std::mt19937 rng(seed);
  const double R = c.radius();
  std::uniform_real_distribution<double> ux(mesh.bbox.min.x() - R, mesh.bbox.max.x() + R);
  std::uniform_real_distribution<double> uy(mesh.bbox.min.y() - R, mesh.bbox.max.y() + R);
  std::vector<Vec2> xy(points);
  for (Vec2& p : xy) p = Vec2(ux(rng), uy(rng));
  std::vector<Drop> out(xy.size());
  s.drop_many(c, xy.data(), xy.size(), out.data());
  int touched = 0;
  for (size_t i = 0; i < xy.size(); ++i) {
    const double ref = reference_drop(c, mesh, xy[i].x(), xy[i].y());
    ASSERT_EQ(out[i].touched, ref > -1e300) << name << " " << cutter_type_name(c.type) << " at " << xy[i].transpose();
    if (!out[i].touched) continue;
    ++touched;
    ASSERT_NEAR(out[i].z, ref, 1e-6) << name << " " << cutter_type_name(c.type) << " at " << xy[i].transpose();
  }
  EXPECT_GT(touched, points / 4) << name;
}

TEST(DropCutter, IndexEqualsReferenceOnPrimitives) {
  unsigned seed = 3;
  for (const char* name : {"cube", "cylinder", "dome", "cone", "cavity"})
    for (const Cutter& c : {Cutter::flat(10), Cutter::ball(6), Cutter::bull(12, 3)})
      expect_equal_to_reference(make_primitive(name), c, 150, seed++, name);
}

TEST(DropCutter, IndexEqualsReferenceOnRealModels) {
  StlReadOptions inch;
  inch.units = Units::Inch;
  const std::pair<const char*, Mesh> models[] = {
      {"mount_rush", read_stl(ROSMILL_TEST_DATA "/mount_rush.stl")},
      {"pycam-textbox", read_stl(ROSMILL_TEST_DATA "/pycam-textbox.stl")},
      {"wheel_in_box", read_stl(ROSMILL_TEST_DATA "/wheel_in_box.stl")},
      {"ktoolcav (inch to mm)", read_stl(ROSMILL_TEST_DATA "/ktoolcav.stl", inch)},
  };
  unsigned seed = 21;
  for (const auto& [name, mesh] : models)
    for (const Cutter& c : {Cutter::flat(10), Cutter::ball(6), Cutter::bull(8, 1)})
      expect_equal_to_reference(mesh, c, 150, seed++, name);
}

// The reference itself against answers known in closed form.
TEST(DropCutter, ReferenceMatchesClosedForms) {
  const Mesh cube = make_primitive("cube");
  EXPECT_NEAR(reference_drop(Cutter::ball(6), cube, 62, 30), 57.0 + std::sqrt(5.0), 1e-9);
  EXPECT_NEAR(reference_drop(Cutter::flat(10), cube, 64.9, 10), 60.0, 1e-12);
  EXPECT_EQ(reference_drop(Cutter::flat(10), cube, 65.1, 10), -std::numeric_limits<double>::infinity());
  const double d = 4.2, e = d - 3.0;
  EXPECT_NEAR(reference_drop(Cutter::bull(10, 2), cube, 60 + d / std::sqrt(2.0), 60 + d / std::sqrt(2.0)),
              60.0 - (2.0 - std::sqrt(4.0 - e * e)), 1e-9);
  const double slope = 0.5, R = 3;
  const Mesh ramp = build_mesh({Vec3(-50, -50, -25), Vec3(50, -50, 25), Vec3(50, 50, 25), Vec3(-50, -50, -25),
                                Vec3(50, 50, 25), Vec3(-50, 50, -25)});
  EXPECT_NEAR(reference_drop(Cutter::ball(6), ramp, 3, 4), 0.5 * 3 + R * std::sqrt(1 + slope * slope) - R, 1e-9);
  const double nz = 1 / std::sqrt(1 + slope * slope);
  EXPECT_NEAR(reference_drop(Cutter::bull(10, 2), ramp, 3, 4), 0.5 * (3 + 3) + 2 / nz - 2, 1e-9);
}

// The gouge decision (branch and bound) agrees with the reference drop of the eroded cutter: just below that
// drop it finds a gouge deeper than the depth, just above it none.
TEST(DropCutter, ReferenceGougeAgreesWithReferenceDrop) {
  const Mesh m = read_stl(ROSMILL_TEST_DATA "/mount_rush.stl");
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ux(-40, 44), uy(-24, 18);
  const double depth = 0.01;
  int checked = 0;
  for (const auto& [c, eroded] : {std::make_pair(Cutter::ball(6), Cutter::ball(6 - 2 * depth)),
                                  std::make_pair(Cutter::flat(10), Cutter::flat(10 - 2 * depth)),
                                  std::make_pair(Cutter::bull(8, 1), Cutter::bull(8 - 2 * depth, 1 - depth))}) {
    for (int i = 0; i < 60; ++i) {
      const double x = ux(rng), y = uy(rng);
      const double z = reference_drop(eroded, m, x, y) - depth;  // tip of the real cutter
      if (z < -1e300) continue;  // nothing under the cutter (the relief is not a full rectangle)
      ++checked;
      EXPECT_TRUE(reference_gouges(c, m, Vec3(x, y, z - 1e-6), depth)) << cutter_type_name(c.type) << " " << x << " " << y;
      EXPECT_FALSE(reference_gouges(c, m, Vec3(x, y, z + 1e-6), depth)) << cutter_type_name(c.type) << " " << x << " " << y;
    }
  }
  EXPECT_GT(checked, 150);
}

// A ball beside a horizontal edge at exactly its radius touches at its equator: the rounding of the distance
// must not lose that contact (the grid of `rosmill dropcutter` starts exactly there, at xmin - R).
TEST(DropCutter, RimTangentEdgeKeepsItsContact) {
  const Mesh box = read_stl(ROSMILL_TEST_DATA "/pycam-textbox.stl");
  const MeshSurface s(box);
  for (double x : {18.0, 27.8, 39.0, 41.8, 88.3}) {
    const Drop d = s.drop(Cutter::ball(6), x, -3.0);
    EXPECT_TRUE(d.touched) << x;
    EXPECT_NEAR(d.z, -3.0, 1e-6) << x;
    EXPECT_EQ(check_drop(Cutter::ball(6), box, x, -3.0, d.z, box.bbox.min.z(), 1e-6), ReferenceCheck::Equal);
  }
}

// The one rim tie of `bench/run dropcutter` (demo2.stl.gz, flat 10, axis at x = -5 on the grid's first column):
// a sloped edge of the wall x = 0 lies at exactly the radius, 5 mm, from the axis, but the rounding of its
// distance put it a hair outside and the cutter fell to the floor. Its triangle, exactly as in the file; the
// answer in closed form is the edge's height at the axis's y.
TEST(DropCutter, FlatRimOnSlopedWallEdgeFromDemo2) {
  const Vec3 a(2.082192, -22.24316, -4.3928060000000002), b(0, -22.24316, -4.3928060000000002),
      c(0, -23.557369999999999, -3.6158800000000002);
  const Mesh tri = one_triangle(a, b, c);
  const double x = -5, y = -23.470588235294109;
  const double on_edge = b.z() + (y - b.y()) / (c.y() - b.y()) * (c.z() - b.z());
  const Drop d = MeshSurface(tri).drop(Cutter::flat(10), x, y);
  EXPECT_TRUE(d.touched);
  EXPECT_NEAR(d.z, on_edge, 1e-12);
  // The reference is right within the 1e-6 but not to the last digit here: at a tangency its chord of
  // the footprint is the square root of a rounding (2.5e-8 mm long along this edge).
  EXPECT_NEAR(reference_drop(Cutter::flat(10), tri, x, y), on_edge, 1e-7);
  EXPECT_EQ(check_drop(Cutter::flat(10), tri, x, y, d.z, tri.bbox.min.z(), 1e-6), ReferenceCheck::Equal);
  // The same tangency for the other shapes, whose contact at the rim is at the edge's height less R.
  for (const Cutter& cutter : {Cutter::ball(10), Cutter::bull(10, 2)}) {
    const Drop e = MeshSurface(tri).drop(cutter, x, y);
    EXPECT_TRUE(e.touched) << cutter_type_name(cutter.type);
    EXPECT_NEAR(e.z, on_edge - cutter.radius() * (cutter.type == CutterType::BallEnd ? 1.0 : 0.4), 1e-9)
        << cutter_type_name(cutter.type);
  }
  // A hair further out nothing is touched.
  EXPECT_FALSE(MeshSurface(tri).drop(Cutter::flat(10), x - 1e-9, y).touched);
}

TEST(DropCutter, OffsetCutterKeepsAllowance) {
  const MeshSurface s(make_primitive("cube"));
  const Cutter g = offset_cutter(Cutter::flat(10), 0.5);
  EXPECT_EQ(g.type, CutterType::BullNose);
  EXPECT_DOUBLE_EQ(g.diameter, 11.0);
  EXPECT_NEAR(s.drop(g, 30, 30).z + 0.5, 60.5, 1e-12);
  // Beside the wall the grown cutter stops 0.5 further out.
  EXPECT_TRUE(s.drop(g, 65.4, 30).touched);
  EXPECT_FALSE(s.drop(g, 65.6, 30).touched);
}

// A wall whose lower edge lies at exactly the cutter's radius from a grid that starts at ymin - R: in double
// ymin - R is -34.794768000000005, 5.0000000000000036 from the edge, and a strict comparison dropped the cutter to
// the floor (0). At the rim's distance, whatever the last bit, the edge, its corners and the boxes around them
// are touched: the flat end mill stands on the edge at its height.
TEST(DropCutter, AnEdgeAtTheRadiusIsTouchedWhateverTheLastBit) {
  const double R = 5.0, ymin = -29.794768;
  const std::vector<Vec3> corners = {{-3.097246, -29.46833, 4.693034}, {-3.131556, -29.794768, 1.570079},
                                     {3.131556, -29.794768, 1.570079},
                                     // a floor far away: the part's lowest height, 0
                                     {100, 100, 0}, {110, 100, 0}, {100, 110, 0}};
  const Mesh mesh = build_mesh(corners);
  const MeshSurface surface(mesh);
  const double y = ymin - R;
  ASSERT_GT(ymin - y, R) << "the premise: the grid's row lies beyond the radius in double";
  const Cutter flat = Cutter::flat(2 * R);
  EXPECT_EQ(surface.drop(flat, -2.8, y).z, 1.570079);       // the edge's interior
  EXPECT_EQ(surface.drop(flat, -3.131556, y).z, 1.570079);  // its corner, straight ahead
  EXPECT_EQ(surface.drop(flat, 3.131556, y).z, 1.570079);
  // A hair further (a micrometre) nothing is under the cutter: the floor.
  EXPECT_EQ(surface.drop(flat, -2.8, y - 1e-6).z, 0.0);
}
