#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/testing/wavy_solid.hpp"

using namespace rosmill::core;

TEST(Mesh, TetrahedronIsClosedAndConsistent) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  std::vector<Vec3> corners = {a, c, b, a, b, d, b, c, d, c, a, d};
  Mesh m = build_mesh(corners);
  MeshReport r = report(m);
  EXPECT_EQ(r.vertices, 4u);
  EXPECT_EQ(r.triangles, 4u);
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.open_edges, 0u);
  EXPECT_EQ(r.inconsistent_edges, 0u);
  EXPECT_NEAR(r.volume, 1.0 / 6.0, 1e-12);
}

// The edges of build_mesh against a plain reference (a sorted map of vertex pairs): same edges in the same
// order, the same faces per edge, the same open / non-manifold / orientation verdicts.
namespace {

void expect_edges_as_reference(const Mesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, std::vector<std::pair<uint32_t, bool>>> ref;  // faces, forward
  for (uint32_t f = 0; f < m.faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = m.faces[f][i], b = m.faces[f][(i + 1) % 3];
      ref[{std::min(a, b), std::max(a, b)}].push_back({f, a < b});
    }
  ASSERT_EQ(m.edges.size(), ref.size());
  size_t id = 0;
  for (const auto& [key, faces] : ref) {
    const MeshEdge& e = m.edges[id];
    EXPECT_EQ(e.a, key.first);
    EXPECT_EQ(e.b, key.second);
    ASSERT_EQ(e.face_count, faces.size());
    for (size_t k = 0; k < faces.size(); ++k) {
      EXPECT_EQ(m.edge_faces[e.first_face + k], faces[k].first);
      const uint32_t f = faces[k].first;
      EXPECT_TRUE(m.face_edges[f][0] == id || m.face_edges[f][1] == id || m.face_edges[f][2] == id);
    }
    EXPECT_EQ(e.consistent, faces.size() != 2 || faces[0].second != faces[1].second) << "edge " << id;
    ++id;
  }
}

}  // namespace

TEST(Mesh, EdgesMatchAPlainReference) {
  for (const std::string& name : primitive_names()) {
    SCOPED_TRACE(name);
    expect_edges_as_reference(make_primitive(name));
  }
  // Large enough for the parallel passes, with a 4,000-facet fan around the bottom centre.
  expect_edges_as_reference(build_mesh(wavy_solid_corners(200, 200.0)));
  // Open, non-manifold (three facets on one edge) and inconsistently oriented facets.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1), e(1, 1, 1);
  expect_edges_as_reference(build_mesh({a, b, c, a, b, d, a, b, e, b, c, e, c, b, d}));
}
