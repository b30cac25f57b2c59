#include <gtest/gtest.h>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/mesh_report.hpp"

using namespace rosmill;

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
