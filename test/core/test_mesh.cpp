#include <gtest/gtest.h>

#include <filesystem>

#include <map>
#include <string>
#include <vector>

#include "bundled_models.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
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

// The report from welded triangles alone (what `rosmill info` prints) against the report of the full Mesh: the
// same counts and the same bits of every sum.
namespace {

MeshReport expect_reports_agree(const IndexedTriangles& t) {
  const MeshReport quick = report(t);
  const MeshReport full = report(mesh_from_indexed(t));
  EXPECT_EQ(quick.triangles, full.triangles);
  EXPECT_EQ(quick.vertices, full.vertices);
  EXPECT_EQ(quick.bbox.min, full.bbox.min);
  EXPECT_EQ(quick.bbox.max, full.bbox.max);
  EXPECT_EQ(quick.area, full.area);
  EXPECT_EQ(quick.volume, full.volume);
  EXPECT_EQ(quick.closed, full.closed);
  EXPECT_EQ(quick.open_edges, full.open_edges);
  EXPECT_EQ(quick.nonmanifold_edges, full.nonmanifold_edges);
  EXPECT_EQ(quick.inconsistent_edges, full.inconsistent_edges);
  EXPECT_EQ(quick.degenerate, full.degenerate);
  return quick;
}

IndexedTriangles welded(const std::vector<Vec3>& corners) { return weld_corners(corners); }

}  // namespace

TEST(MeshReport, TrianglesAloneGiveTheFullMeshReportOnEveryBundledModel) {
  for (const test_data::BundledModel& model : test_data::kBundledModels) {
    SCOPED_TRACE(model.file);
    StlReadOptions o;
    o.units = model.units;
    // The small models are in test/data; the large ones only where ../shared/data is beside the checkout.
    const std::string path = model.small ? std::string(ROSMILL_TEST_DATA "/") + model.file
                                         : std::string(ROSMILL_SHARED_DATA "/stl/") + model.file;
    if (!model.small && !std::filesystem::exists(path)) continue;
    const IndexedTriangles t = read_stl_triangles(path, o);
    const MeshReport r = expect_reports_agree(t);
    EXPECT_GT(r.area, 0.0);
  }
  for (const std::string& name : primitive_names()) {
    SCOPED_TRACE(name);
    const Mesh m = make_primitive(name);
    expect_reports_agree({m.vertices, m.faces});
  }
}

TEST(MeshReport, TrianglesAloneGiveTheFullMeshReportOnHostileMeshes) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1), e(1, 1, 1), mid(0.5, 0, 0);
  const std::vector<Vec3> tetra = {a, c, b, a, b, d, b, c, d, c, a, d};
  const MeshReport closed = expect_reports_agree(welded(tetra));
  EXPECT_TRUE(closed.closed);
  EXPECT_EQ(closed.volume, 1.0 / 6.0);

  // Open: the last facet missing, its three edges have one facet each.
  const MeshReport open = expect_reports_agree(welded({tetra.begin(), tetra.end() - 3}));
  EXPECT_FALSE(open.closed);
  EXPECT_EQ(open.open_edges, 3u);

  // Flipped: one facet runs the other way round; each of its three edges meets a neighbour in the same direction.
  std::vector<Vec3> flipped = tetra;
  std::swap(flipped[1], flipped[2]);
  const MeshReport flip = expect_reports_agree(welded(flipped));
  EXPECT_TRUE(flip.closed);
  EXPECT_EQ(flip.inconsistent_edges, 3u);

  // Non-manifold: three facets on edge a-b and three on b-c; degenerate: a facet with a repeated corner and a flat one.
  const MeshReport fan = expect_reports_agree(welded({a, b, c, a, b, d, a, b, e, b, c, e, c, b, d}));
  EXPECT_EQ(fan.nonmanifold_edges, 2u);
  std::vector<Vec3> degenerate = tetra;
  for (const Vec3& p : {a, a, b, a, mid, b}) degenerate.push_back(p);
  const MeshReport flat = expect_reports_agree(welded(degenerate));
  EXPECT_EQ(flat.degenerate, 2u);
  EXPECT_EQ(flat.area, closed.area);

  // Large enough for both cores, with facets flipped and removed here and there.
  std::vector<Vec3> wavy = wavy_solid_corners(200, 200.0);
  for (size_t f = 0; f + 3 <= wavy.size(); f += 3 * 997) std::swap(wavy[f], wavy[f + 1]);
  const MeshReport whole = expect_reports_agree(welded(wavy));
  EXPECT_TRUE(whole.closed);
  EXPECT_GT(whole.inconsistent_edges, 0u);
  wavy.erase(wavy.begin() + 3 * 5000, wavy.begin() + 3 * 5003);
  const MeshReport holed = expect_reports_agree(welded(wavy));
  EXPECT_FALSE(holed.closed);
  EXPECT_GT(holed.open_edges, 0u);
}

TEST(MeshReport, AFaceBeyondTheVerticesIsRefusedAsTheFullMeshRefusesIt) {
  IndexedTriangles t = weld_corners({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
  t.faces.push_back({0, 7, 1});
  std::string quick, full;
  try {
    report(t);
  } catch (const Error& e) {
    quick = e.what();
  }
  try {
    mesh_from_indexed(t);
  } catch (const Error& e) {
    full = e.what();
  }
  EXPECT_NE(quick.find("vertex 7 of 3"), std::string::npos) << quick;
  EXPECT_EQ(quick, full);
}
