// Phase 2 segmentations of real models checked against what any correct one must satisfy, facet by facet and
// edge by edge (the brute-force answer computed here from the mesh): a partition of the facets, areas, neighbours
// across every shared edge, boundary loops made of exactly the border half-edges, connected segments, and no
// small segment left with a neighbour. Both ways phase 2 is computed are checked: patch by patch (the default
// rule: no phase 1 patch is small) and one recombination across patches (a rule that finds small phase 1 patches).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "rosmill/io/stl.hpp"
#include "rosmill/segment/setup_segmentation.hpp"

using namespace rosmill::core;
using namespace rosmill::core::segment;

namespace {

using HalfEdges = std::multiset<std::pair<uint32_t, uint32_t>>;

bool small(const SizeRule& rule, const Patch& p, double total_area) {
  return rule.kind == SizeRule::Kind::FacetCount ? p.facet_count < rule.min_facets
                                                 : p.area < rule.min_area_fraction * total_area;
}

void check_partition(const Mesh& m, const SetupSegmentation& s) {
  ASSERT_EQ(s.labels().size(), m.face_count());
  std::vector<uint32_t> order = s.facet_order();
  std::sort(order.begin(), order.end());
  for (uint32_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i);
  uint32_t offset = 0, last_first = 0;
  for (const Segment& seg : s.segments()) {
    ASSERT_EQ(seg.shape.first_facet, offset);
    const uint32_t* f = s.facet_order().data() + offset;
    ASSERT_GT(seg.shape.facet_count, 0u);
    // Numbered by first facet; ascending inside a segment.
    if (seg.shape.id > 0) {
      EXPECT_GT(f[0], last_first);
    }
    last_first = f[0];
    double area = 0, reach = 0;
    for (uint32_t i = 0; i < seg.shape.facet_count; ++i) {
      EXPECT_EQ(s.labels()[f[i]], seg.shape.id);
      if (i > 0) {
        EXPECT_LT(f[i - 1], f[i]);
      }
      area += m.areas[f[i]];
      if (s.reachable()[f[i]]) reach += m.areas[f[i]];
    }
    EXPECT_NEAR(seg.shape.area, area, 1e-9 * (area + 1));
    EXPECT_NEAR(seg.reachable_area, reach, 1e-9 * (area + 1));
    if (area > 0) {
      EXPECT_EQ(seg.reachable, reach >= 0.5 * area);
    }
    offset += seg.shape.facet_count;
  }
}

// Neighbours, connectivity and loops against the edges of the mesh.
void check_borders(const Mesh& m, const SetupSegmentation& s) {
  const size_t n = s.count();
  std::vector<std::set<uint32_t>> neighbours(n);
  std::vector<uint32_t> link(m.face_count());  // union-find over the facets across shared edges of one segment
  for (uint32_t f = 0; f < m.face_count(); ++f) link[f] = f;
  auto find = [&](uint32_t x) {
    while (link[x] != x) x = link[x] = link[link[x]];
    return x;
  };
  for (const MeshEdge& e : m.edges) {
    for (uint32_t i = 0; i < e.face_count; ++i)
      for (uint32_t j = i + 1; j < e.face_count; ++j) {
        const uint32_t f = m.edge_faces[e.first_face + i], g = m.edge_faces[e.first_face + j];
        const uint32_t a = s.labels()[f], b = s.labels()[g];
        if (a != b) {
          neighbours[a].insert(b);
          neighbours[b].insert(a);
        } else {
          link[find(f)] = find(g);
        }
      }
  }
  std::vector<HalfEdges> border(n);
  for (uint32_t f = 0; f < m.face_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
      const uint32_t g = m.neighbour(f, k);
      if (a == b || (g != kNone && s.labels()[g] == s.labels()[f])) continue;
      border[s.labels()[f]].insert({a, b});
    }
  for (const Segment& seg : s.segments()) {
    const uint32_t id = seg.shape.id;
    EXPECT_EQ(std::vector<uint32_t>(neighbours[id].begin(), neighbours[id].end()), seg.shape.neighbours)
        << "segment " << id;
    const uint32_t* f = s.facet_order().data() + seg.shape.first_facet;
    std::set<uint32_t> components;
    for (uint32_t i = 0; i < seg.shape.facet_count; ++i) components.insert(find(f[i]));
    EXPECT_EQ(components.size(), 1u) << "segment " << id << " is not connected";
    HalfEdges traced;
    for (const BoundaryLoop& loop : seg.shape.loops) {
      const size_t k = loop.vertices.size();
      for (size_t i = 0; i + 1 < k; ++i) traced.insert({loop.vertices[i], loop.vertices[i + 1]});
      if (loop.closed) traced.insert({loop.vertices[k - 1], loop.vertices[0]});
    }
    EXPECT_EQ(traced, border[id]) << "segment " << id << " loops";
  }
}

void check(const Mesh& m, const SurfacePatches& sp, const SetupSegmentation& s, const SizeRule& rule,
           bool within_patches) {
  check_partition(m, s);
  check_borders(m, s);
  for (const Segment& seg : s.segments()) {
    // Recombination is complete: a small segment has no neighbour to join.
    if (small(rule, seg.shape, sp.total_area())) {
      EXPECT_TRUE(seg.shape.neighbours.empty()) << seg.shape.id;
    }
    const uint32_t* f = s.facet_order().data() + seg.shape.first_facet;
    EXPECT_EQ(seg.patch, sp.label(f[0]));
    if (!within_patches) continue;
    for (uint32_t i = 0; i < seg.shape.facet_count; ++i) ASSERT_EQ(sp.label(f[i]), seg.patch);
  }
}

class SegmentInvariants : public ::testing::TestWithParam<std::string> {};

TEST_P(SegmentInvariants, HoldForEverySetupAndBothRecombinations) {
  const Mesh m = read_stl(std::string(ROSMILL_TEST_DATA) + "/" + GetParam());
  const SurfacePatches sp = segment_surface(m);
  // Inner neighbours: the same-patch facet across each manifold edge, by position.
  std::vector<uint32_t> position(m.face_count());
  for (uint32_t i = 0; i < m.face_count(); ++i) position[sp.facet_order()[i]] = i;
  for (uint32_t i = 0; i < m.face_count(); ++i)
    for (int k = 0; k < 3; ++k) {
      const uint32_t f = sp.facet_order()[i], g = m.neighbour(f, k);
      const bool inner = g != kNone && sp.label(g) == sp.label(f);
      ASSERT_EQ(sp.inner_neighbours()[i][k], inner ? position[g] : kNone);
    }

  const EgiSet egis(sp);
  SizeRule by_facets;  // small phase 1 patches with neighbours: segments may merge across patches
  by_facets.kind = SizeRule::Kind::FacetCount;
  by_facets.min_facets = 40;
  bool some_small = false;
  for (const Patch& p : sp.patches()) some_small = some_small || (p.facet_count < 40 && !p.neighbours.empty());
  ASSERT_TRUE(some_small);
  size_t split_apart = 0;
  for (const char* name : {"+z", "-x", "+y", "4axis:y", "5axis"}) {
    SCOPED_TRACE(name);
    const SetupSegmentation s = segment_setup(egis, parse_setup(name));
    check(m, sp, s, sp.options().small, true);
    split_apart += s.count() > sp.count();
    check(m, sp, segment_setup(egis, parse_setup(name), &by_facets), by_facets, false);
  }
  EXPECT_GE(split_apart, 3u);  // the models have patches the setups cut
}

INSTANTIATE_TEST_SUITE_P(Models, SegmentInvariants,
                         ::testing::Values("ktoolcav.stl", "wheel_in_box.stl", "mount_rush.stl", "featuretype.STL"),
                         [](const auto& info) {
                           std::string n = info.param;
                           return n.substr(0, n.find('.'));
                         });

}  // namespace
