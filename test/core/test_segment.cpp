// Phase 1 of the segmentation (surface flooding + recombination) on the seed primitives and hand-built meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/segment/surface_patches.hpp"

using namespace rosmill::core;
using namespace rosmill::core::segment;

namespace {

// Every facet is in exactly one patch, and the patch records agree with the labels.
void expect_partition(const SurfacePatches& sp) {
  const Mesh& m = sp.mesh();
  ASSERT_EQ(sp.labels().size(), m.face_count());
  std::vector<int> seen(m.face_count(), 0);
  size_t facets = 0;
  double area = 0.0;
  for (const Patch& p : sp.patches()) {
    EXPECT_GT(p.facet_count, 0u);
    for (const uint32_t* f = sp.facets_begin(p); f != sp.facets_end(p); ++f) {
      ++seen[*f];
      EXPECT_EQ(sp.label(*f), p.id);
    }
    facets += p.facet_count;
    area += p.area;
  }
  EXPECT_EQ(facets, m.face_count());
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
  EXPECT_NEAR(area, sp.total_area(), 1e-9 * sp.total_area());
}

// A closed mesh's patches are bounded by closed loops, and neighbourhood is symmetric.
void expect_closed_loops_and_symmetry(const SurfacePatches& sp) {
  for (const Patch& p : sp.patches()) {
    for (const BoundaryLoop& l : p.loops) {
      EXPECT_TRUE(l.closed);
      EXPECT_FALSE(l.mesh_border);
      EXPECT_GE(l.vertices.size(), 3u);
    }
    for (uint32_t q : p.neighbours) {
      const auto& back = sp.patch(q).neighbours;
      EXPECT_TRUE(std::binary_search(back.begin(), back.end(), p.id));
    }
  }
}

SurfacePatches segment_primitive(const std::string& name, Mesh& holder) {
  holder = make_primitive(name);
  SurfacePatches sp = segment_surface(holder);
  expect_partition(sp);
  expect_closed_loops_and_symmetry(sp);
  return sp;
}

// Patch whose mean normal is closest to `n`.
const Patch& patch_facing(const SurfacePatches& sp, const Vec3& n) {
  return *std::max_element(sp.patches().begin(), sp.patches().end(),
                           [&](const Patch& a, const Patch& b) { return a.normal.dot(n) < b.normal.dot(n); });
}

void tri(std::vector<Vec3>& c, const Vec3& a, const Vec3& b, const Vec3& d) {
  c.push_back(a);
  c.push_back(b);
  c.push_back(d);
}

// A torus (R 40, r 15) of nu x nv quads: smooth and closed, no poles.
std::vector<Vec3> torus_corners(int nu, int nv) {
  auto p = [&](int i, int j) {
    const double u = 2 * M_PI * (i % nu) / nu, v = 2 * M_PI * (j % nv) / nv;
    return Vec3((40 + 15 * std::cos(v)) * std::cos(u), (40 + 15 * std::cos(v)) * std::sin(u), 15 * std::sin(v));
  };
  std::vector<Vec3> c;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      tri(c, p(i, j), p(i + 1, j), p(i + 1, j + 1));
      tri(c, p(i, j), p(i + 1, j + 1), p(i, j + 1));
    }
  return c;
}

}  // namespace

TEST(SegmentPhase1, CubeHasSixFaces) {
  Mesh m;
  const SurfacePatches sp = segment_primitive("cube", m);
  ASSERT_EQ(sp.count(), 6u);
  for (const Patch& p : sp.patches()) {
    EXPECT_EQ(p.facet_count, 2u);
    EXPECT_NEAR(p.area, 3600.0, 1e-9);
    EXPECT_EQ(p.neighbours.size(), 4u);  // each face touches all but its opposite
    ASSERT_EQ(p.loops.size(), 1u);
    EXPECT_EQ(p.loops[0].vertices.size(), 4u);
    EXPECT_NEAR(std::abs(p.normal.x()) + std::abs(p.normal.y()) + std::abs(p.normal.z()), 1.0, 1e-12);
  }
}

TEST(SegmentPhase1, CylinderHasTwoCapsAndOneSide) {
  Mesh m;
  const SurfacePatches sp = segment_primitive("cylinder", m);
  ASSERT_EQ(sp.count(), 3u);
  const Patch& top = patch_facing(sp, Vec3::UnitZ());
  const Patch& bottom = patch_facing(sp, -Vec3::UnitZ());
  EXPECT_EQ(top.facet_count, 36u);
  EXPECT_EQ(bottom.facet_count, 36u);
  for (const Patch& p : sp.patches())
    if (p.id != top.id && p.id != bottom.id) {
      EXPECT_EQ(p.facet_count, 72u);         // the side: 36 quads
      EXPECT_EQ(p.loops.size(), 2u);         // its two rims
      EXPECT_NEAR(p.normal.norm(), 0.0, 1e-9);  // the side's normals cancel around the axis
    }
}

TEST(SegmentPhase1, ConeHasBaseAndSide) {
  Mesh m;
  const SurfacePatches sp = segment_primitive("cone", m);
  ASSERT_EQ(sp.count(), 2u);
  EXPECT_EQ(patch_facing(sp, -Vec3::UnitZ()).facet_count, 36u);
  EXPECT_EQ(patch_facing(sp, Vec3::UnitZ()).facet_count, 36u);
}

TEST(SegmentPhase1, DomeHasBaseAndDome) {
  Mesh m;
  const SurfacePatches sp = segment_primitive("dome", m);
  ASSERT_EQ(sp.count(), 2u);
  const Patch& base = patch_facing(sp, -Vec3::UnitZ());
  EXPECT_NEAR(base.normal.z(), -1.0, 1e-12);
  EXPECT_EQ(base.facet_count + patch_facing(sp, Vec3::UnitZ()).facet_count, 900u);
  EXPECT_NEAR(patch_facing(sp, Vec3::UnitZ()).area, 2 * M_PI * 50 * 50, 0.02 * 2 * M_PI * 50 * 50);
}

TEST(SegmentPhase1, CavityIsBlockFacesPlusOnePocket) {
  // Cylindrical block r60 z 0..60 with a hemispherical pocket r50 from the top: the top annulus, the side, the
  // bottom and the pocket.
  Mesh m;
  const SurfacePatches sp = segment_primitive("cavity", m);
  ASSERT_EQ(sp.count(), 4u);
  const Patch& bottom = patch_facing(sp, -Vec3::UnitZ());
  EXPECT_NEAR(bottom.normal.z(), -1.0, 1e-12);
  int annulus = 0, pocket = 0, side = 0;
  // Both rims are 30-gons.
  const double pocket_area = 2 * M_PI * 50 * 50, annulus_area = 15 * std::sin(2 * M_PI / 30) * (60 * 60 - 50 * 50);
  for (const Patch& p : sp.patches()) {
    if (p.id == bottom.id) continue;
    if (std::abs(p.normal.z()) < 1e-9) {
      ++side;  // the block's wall: normals cancel in x and y
      EXPECT_EQ(p.loops.size(), 2u);
    } else if (std::abs(p.area - annulus_area) < 1e-6 * annulus_area) {
      ++annulus;
      EXPECT_NEAR(p.normal.z(), 1.0, 1e-12);
      EXPECT_EQ(p.loops.size(), 2u);  // outer rim and the pocket's rim
    } else {
      ++pocket;
      // A bowl's outward (solid) normals point into the pocket; their area-weighted mean is +Z by symmetry.
      EXPECT_NEAR(p.area, pocket_area, 0.02 * pocket_area);
      EXPECT_NEAR(p.normal.z(), 1.0, 1e-9);
      EXPECT_EQ(p.loops.size(), 1u);
      EXPECT_EQ(p.neighbours.size(), 1u);  // only the annulus
    }
  }
  EXPECT_EQ(annulus, 1);
  EXPECT_EQ(side, 1);
  EXPECT_EQ(pocket, 1);
}

TEST(SegmentPhase1, FineSmoothClosedBodyIsOnePatch) {
  Mesh m = build_mesh(torus_corners(96, 48));
  ASSERT_TRUE(m.closed());
  const SurfacePatches sp = segment_surface(m);
  expect_partition(sp);
  EXPECT_EQ(sp.count(), 1u);
  EXPECT_EQ(sp.notes().patches_before_recombination, 1u);
  EXPECT_TRUE(sp.patch(0).loops.empty());  // a closed surface in one patch has no border
}

TEST(SegmentPhase1, ThresholdDecidesASmoothBody) {
  // 12 x 6 torus: neighbouring normals differ by up to 60 degrees (|dn| ~ 1.0): a 0.4 threshold cuts it up,
  // a 1.5 threshold does not.
  Mesh m = build_mesh(torus_corners(12, 6));
  SegmentOptions loose;
  loose.threshold = 1.5;
  EXPECT_EQ(segment_surface(m, loose).count(), 1u);
  SegmentOptions strict;
  strict.small.min_area_fraction = 0.0;
  EXPECT_GT(segment_surface(m, strict).count(), 1u);
}

namespace {

// Triangle a, b, c turned so that its normal points along `out`.
void tri_out(std::vector<Vec3>& c, const Vec3& a, const Vec3& b, const Vec3& d, const Vec3& out) {
  if ((b - a).cross(d - a).dot(out) >= 0)
    tri(c, a, b, d);
  else
    tri(c, a, d, b);
}

// A 60 x 60 x 20 block whose top is a fan of 2,400 needles (aspect ratio up to 1,700) from the corner (0,0) to
// the far edges, with a cap (a triangle with an angle near 180 degrees) beside each of the two near edges, lifted
// by `lift` so that the cap tilts away from the top. The two far walls are fans of needles too. Six faces.
std::vector<Vec3> needle_block(double lift) {
  const double s = 60.0, h = 20.0, step = 0.05;
  const int per_edge = int(std::lround(s / step));
  std::vector<Vec3> chain;  // (s,0) -> (s,s) -> (0,s) at height h
  for (int k = 0; k <= per_edge; ++k) chain.emplace_back(s, k * step, h);
  for (int k = 1; k <= per_edge; ++k) chain.emplace_back(s - k * step, s, h);
  std::vector<Vec3> c;
  const Vec3 o(0, 0, h), up(0, 0, 1);
  const size_t last = chain.size() - 1;
  // Top: the caps beside the near edges o - chain[0] and chain[last] - o, then the needles between them.
  const Vec3 cap0(30, 0.01, h + lift), cap1(0.01, 30, h + lift);
  tri_out(c, o, chain[0], cap0, up);
  tri_out(c, cap0, chain[0], chain[1], up);
  tri_out(c, o, cap0, chain[1], up);
  tri_out(c, o, chain[last], cap1, up);
  tri_out(c, cap1, chain[last - 1], chain[last], up);
  tri_out(c, o, chain[last - 1], cap1, up);
  for (size_t k = 1; k + 1 < last; ++k) tri_out(c, o, chain[k], chain[k + 1], up);
  // Far walls: fans from their bottom corners.
  const Vec3 b0(s, 0, 0), b1(s, s, 0), b2(0, s, 0), b3(0, 0, 0);
  const size_t corner = size_t(per_edge);
  for (size_t k = 0; k < corner; ++k) tri_out(c, b0, chain[k], chain[k + 1], Vec3::UnitX());
  tri_out(c, b0, chain[corner], b1, Vec3::UnitX());
  for (size_t k = corner; k < last; ++k) tri_out(c, b2, chain[k], chain[k + 1], Vec3::UnitY());
  tri_out(c, b2, b1, chain[corner], Vec3::UnitY());
  // Near walls and bottom: plain quads.
  tri_out(c, b3, b0, chain[0], -Vec3::UnitY());
  tri_out(c, b3, chain[0], o, -Vec3::UnitY());
  tri_out(c, b3, b2, chain[last], -Vec3::UnitX());
  tri_out(c, b3, chain[last], o, -Vec3::UnitX());
  tri_out(c, b3, b0, b1, -Vec3::UnitZ());
  tri_out(c, b3, b1, b2, -Vec3::UnitZ());
  return c;
}

}  // namespace

TEST(SegmentPhase1, NeedlesAndCapsMakeNoSpuriousPatches) {
  // Flat needles join by the flood itself; the lifted caps (tilted 45 degrees) are patches of their own after
  // the flood, and recombination folds them back into the top, the neighbour they share most boundary with.
  Mesh m = build_mesh(needle_block(0.01));
  ASSERT_TRUE(m.closed());
  const SurfacePatches sp = segment_surface(m);
  expect_partition(sp);
  expect_closed_loops_and_symmetry(sp);
  EXPECT_GE(sp.notes().patches_before_recombination, 8u);
  ASSERT_EQ(sp.count(), 6u);
  // A cap shares its long edge with a wall and its two short ones with tilted slivers, so the wall can be its
  // dominant neighbour: the top keeps at least everything but the two caps (0.3 mm2 each).
  const Patch& top = patch_facing(sp, Vec3::UnitZ());
  EXPECT_NEAR(top.area, 3600.0, 0.7);
  EXPECT_GE(top.facet_count, 2402u);
  // Without recombination the caps stay: the flood never drops or duplicates a facet either way.
  SegmentOptions none;
  none.small.min_area_fraction = 0.0;
  const SurfacePatches raw = segment_surface(m, none);
  expect_partition(raw);
  EXPECT_EQ(raw.count(), sp.notes().patches_before_recombination);
  // Caps in the plane (not lifted) are not even cut by the flood.
  Mesh flat = build_mesh(needle_block(0.0));
  EXPECT_EQ(segment_surface(flat, none).count(), 6u);
}

TEST(SegmentPhase1, ZeroAreaFacetsJoinANeighbourAndNeverMakePatches) {
  // A cube with a zero-area sliver in its top face: the top's diagonal a-c gets a midpoint m, and the facet
  // (a, m, c) is degenerate. The top's two triangles touch only through it.
  std::vector<Vec3> c = cube_corners(60.0);
  Mesh cube = build_mesh(c);
  // Find the top's two triangles and rebuild them around the sliver.
  std::vector<Vec3> out;
  std::vector<Vec3> top;
  for (size_t t = 0; t < c.size(); t += 3) {
    if (c[t].z() == 60 && c[t + 1].z() == 60 && c[t + 2].z() == 60)
      top.insert(top.end(), c.begin() + t, c.begin() + t + 3);
    else
      out.insert(out.end(), c.begin() + t, c.begin() + t + 3);
  }
  ASSERT_EQ(top.size(), 6u);
  // quad(p4, p5, p6, p7): triangles (p4, p5, p6) and (p4, p6, p7) share the diagonal p4-p6.
  const Vec3 p4 = top[0], p5 = top[1], p6 = top[2], p7 = top[5], mid = 0.5 * (p4 + p6);
  tri(out, p4, p5, p6);
  tri(out, p4, mid, p6);  // zero area, its corners on one line
  tri(out, p4, p6, mid);  // and its twin, closing the sliver
  tri(out, p4, p6, p7);
  Mesh m = build_mesh(out);
  const SurfacePatches sp = segment_surface(m);
  expect_partition(sp);
  EXPECT_EQ(sp.notes().degenerate_facets, 2u);
  EXPECT_EQ(sp.count(), 6u);
  EXPECT_EQ(sp.notes().patches_before_recombination, 6u);  // bridged by the flood, not rescued by recombination
  EXPECT_EQ(patch_facing(sp, Vec3::UnitZ()).facet_count, 4u);
}

TEST(SegmentPhase1, OpenMeshIsSegmentedAndItsBorderReported) {
  // The cube without its top: five patches, the open rim reported as mesh border on each wall's loop.
  std::vector<Vec3> c = cube_corners(60.0), out;
  for (size_t t = 0; t < c.size(); t += 3)
    if (!(c[t].z() == 60 && c[t + 1].z() == 60 && c[t + 2].z() == 60)) out.insert(out.end(), c.begin() + t, c.begin() + t + 3);
  Mesh m = build_mesh(out);
  const SurfacePatches sp = segment_surface(m);
  expect_partition(sp);
  EXPECT_EQ(sp.count(), 5u);
  EXPECT_EQ(sp.notes().open_edges, 4u);
  for (const Patch& p : sp.patches()) {
    ASSERT_EQ(p.loops.size(), 1u);
    EXPECT_TRUE(p.loops[0].closed);
  }
}

TEST(SegmentPhase1, NonManifoldMeshIsSegmentedAndReported) {
  // Two cubes sharing one edge (four facets on it), and a fin standing on a third cube's top.
  std::vector<Vec3> c = cube_corners(10.0);
  for (const Vec3& p : cube_corners(10.0)) c.push_back(p + Vec3(10, 10, 0));
  Mesh m = build_mesh(c);
  const SurfacePatches sp = segment_surface(m);
  expect_partition(sp);
  EXPECT_EQ(sp.notes().nonmanifold_edges, 1u);
  EXPECT_EQ(sp.count(), 12u);

  // A fin standing on the top's diagonal (0,0,10)-(10,10,10): that edge has three facets.
  std::vector<Vec3> f = cube_corners(10.0);
  tri(f, Vec3(0, 0, 10), Vec3(10, 10, 10), Vec3(5, 5, 15));
  Mesh fin = build_mesh(f);
  const SurfacePatches fp = segment_surface(fin);
  expect_partition(fp);
  EXPECT_EQ(fp.notes().open_edges, 2u);
  EXPECT_EQ(fp.notes().nonmanifold_edges, 1u);
  // The top's two facets still join across the non-manifold edge (same normal); the fin is its own patch.
  EXPECT_EQ(fp.count(), 7u);
}

TEST(SegmentPhase1, RejectsBadOptions) {
  Mesh m = make_primitive("cube");
  SegmentOptions o;
  o.threshold = 0.0;
  EXPECT_THROW(segment_surface(m, o), Error);
  o.threshold = 0.4;
  o.small.min_area_fraction = 1.5;
  EXPECT_THROW(segment_surface(m, o), Error);
}

TEST(SegmentPhase1, FacetCountRuleMergesSmallPatches) {
  // With "fewer than 3 facets is small", every cube face (2 facets) is small: they merge until one is left.
  Mesh m = make_primitive("cube");
  SegmentOptions o;
  o.small.kind = SizeRule::Kind::FacetCount;
  o.small.min_facets = 3;
  const SurfacePatches sp = segment_surface(m, o);
  expect_partition(sp);
  EXPECT_EQ(sp.count(), 1u);
  // On the cylinder, 36-facet caps survive a rule of 30 facets.
  Mesh cyl = make_primitive("cylinder");
  o.small.min_facets = 30;
  EXPECT_EQ(segment_surface(cyl, o).count(), 3u);
}
