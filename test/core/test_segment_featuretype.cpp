// featuretype.STL (trimesh's machined-feature test part, inch) segmented at the default threshold: each planar
// face and each cylindrical wall is its own patch.
//
// The count, established by inspection of the part's patches (normals, areas, loops) and checked here by
// property: 57 patches = 35 planar faces + 22 cylindrical walls.
//  - planar (35): the top face (11 loops: its outline and the openings in it), the bottom (9 loops), the outer
//    sides and a 45 degree chamfer, a rectangular pocket's four walls and floor, eight counterbores' annular
//    floors, and the small faces of the slots and steps;
//  - cylindrical (22): the eight counterbores' two walls each (16), and six other round walls (bores, a rounded
//    end and fillet-like walls, axes along X, Y or Z).
// What makes the count right is not the number alone but that (1) every patch is exactly one plane or exactly
// one cylinder — no face is glued to a neighbour — and (2) every edge between two patches is a sharp edge —
// no face or wall is cut in two.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "rosmill/io/stl.hpp"
#include "rosmill/segment/surface_patches.hpp"

using namespace rosmill::core;
using namespace rosmill::core::segment;

namespace {

enum class Shape { Plane, Cylinder, Other };

// A plane: every facet normal equals the first. A cylinder: every facet normal is perpendicular to one axis
// (the normals' scatter matrix has a zero eigenvalue) and they are not all equal.
Shape shape_of(const SurfacePatches& sp, const Patch& p) {
  const Mesh& m = sp.mesh();
  const Vec3 n0 = m.normals[*sp.facets_begin(p)];
  double spread = 0.0;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const uint32_t* f = sp.facets_begin(p); f != sp.facets_end(p); ++f) {
    spread = std::max(spread, (m.normals[*f] - n0).norm());
    scatter += m.normals[*f] * m.normals[*f].transpose();
  }
  if (spread < 1e-4) return Shape::Plane;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  return eig.eigenvalues()(0) < 1e-6 * scatter.trace() ? Shape::Cylinder : Shape::Other;
}

}  // namespace

TEST(SegmentFeatureType, EachFaceAndEachWallIsItsOwnPatch) {
  StlReadOptions options;
  options.units = Units::Inch;
  const Mesh mesh = read_stl(ROSMILL_TEST_DATA "/featuretype.STL", options);
  const SurfacePatches sp = segment_surface(mesh);
  EXPECT_EQ(sp.notes().patches_before_recombination, sp.count()) << "no face needed the recombination";
  int planes = 0, cylinders = 0;
  for (const Patch& p : sp.patches()) {
    const Shape s = shape_of(sp, p);
    EXPECT_NE(s, Shape::Other) << "patch " << p.id << " (" << p.facet_count << " facets) mixes surfaces";
    planes += s == Shape::Plane;
    cylinders += s == Shape::Cylinder;
  }
  EXPECT_EQ(sp.count(), 57u);
  EXPECT_EQ(planes, 35);
  EXPECT_EQ(cylinders, 22);
  // Every manifold edge between two patches is sharp (normals at least the threshold apart).
  size_t borders = 0;
  for (const MeshEdge& e : mesh.edges) {
    if (e.face_count != 2) continue;
    const uint32_t f0 = mesh.edge_faces[e.first_face], f1 = mesh.edge_faces[e.first_face + 1];
    if (sp.label(f0) == sp.label(f1)) continue;
    ++borders;
    EXPECT_GE((mesh.normals[f0] - mesh.normals[f1]).norm(), 0.4) << "patches " << sp.label(f0) << " and "
                                                                  << sp.label(f1) << " meet at a smooth edge";
  }
  EXPECT_GT(borders, 0u);
  // The file's 576 open edges are float noise between walls (no hole in the part): welding at 1e-4 mm closes
  // them, and the segmentation does not change.
  EXPECT_EQ(sp.notes().open_edges, 576u);
  options.weld.tolerance = 1e-4;
  const Mesh welded = read_stl(ROSMILL_TEST_DATA "/featuretype.STL", options);
  EXPECT_TRUE(welded.closed());
  EXPECT_EQ(segment_surface(welded).count(), 57u);
}
