// Phase 1 of the segmentation (surface flooding + recombination) on the seed primitives and hand-built meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "rosmill/geometry/primitives.hpp"
#include "rosmill/segment/surface_patches.hpp"

using namespace rosmill;
using namespace rosmill::segment;

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
