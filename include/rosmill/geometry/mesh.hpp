// An indexed triangle mesh with welded vertices, recomputed face normals and edge adjacency.
//
// Every consumer (slicing, segmentation, drop-cutter, ROS markers) reads this one structure; it is built once
// from a triangle soup (three corners per triangle, as STL stores them) by build_mesh().
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

constexpr uint32_t kNone = 0xffffffffu;

// An undirected edge between two welded vertices (a < b) and the faces that use it.
struct MeshEdge {
  uint32_t a = kNone, b = kNone;
  // Index of the first face using this edge in Mesh::edge_faces; face_count entries follow.
  uint32_t first_face = 0;
  uint32_t face_count = 0;
  // For a manifold edge (two faces): true when the two faces run it in opposite directions, as a consistently
  // oriented surface does.
  bool consistent = true;

  bool boundary() const { return face_count == 1; }
  bool manifold() const { return face_count == 2; }
  bool nonmanifold() const { return face_count > 2; }
};

class Mesh {
 public:
  using Face = std::array<uint32_t, 3>;

  std::vector<Vec3> vertices;
  std::vector<Face> faces;
  // Unit normal of each face from its corners (right-hand rule); zero for a degenerate face.
  std::vector<Vec3> normals;
  std::vector<double> areas;
  // face_edges[f][i] is the edge from corner i to corner (i+1)%3 of face f.
  std::vector<std::array<uint32_t, 3>> face_edges;
  std::vector<MeshEdge> edges;
  // Faces of each edge, grouped per edge (see MeshEdge::first_face).
  std::vector<uint32_t> edge_faces;
  Box3 bbox;

  size_t face_count() const { return faces.size(); }
  size_t vertex_count() const { return vertices.size(); }
  const Vec3& corner(size_t f, int i) const { return vertices[faces[f][i]]; }

  // The face across edge i of face f, or kNone when the edge is open or non-manifold.
  // Inline: the floods of segmentation call it for every facet.
  uint32_t neighbour(size_t f, int i) const {
    const MeshEdge& e = edges[face_edges[f][i]];
    if (e.face_count != 2) return kNone;
    const uint32_t f0 = edge_faces[e.first_face], f1 = edge_faces[e.first_face + 1];
    return f0 == f ? f1 : f0;
  }
  // True when every edge has exactly two faces.
  bool closed() const;
};

struct WeldOptions {
  // 0: corners weld only when bit-for-bit equal (after -0 == +0). > 0: corners closer than this weld.
  double tolerance = 0.0;
};

// Welded triangles: the vertices (in order of first appearance) and the faces that index them, before the
// derived data of a Mesh. What a viewer needs, and what the well-known STL readers stop at.
struct IndexedTriangles {
  std::vector<Vec3> vertices;
  std::vector<Mesh::Face> faces;
};

// The cross product of a face's edges from its first corner: its normal times twice its area; zero for a
// degenerate face (a repeated vertex, or corners on one line), the one rule for "degenerate" everywhere.
Vec3 face_cross(const std::vector<Vec3>& vertices, const Mesh::Face& face);

// Welds corners (3 per triangle) into vertices and faces.
IndexedTriangles weld_corners(const std::vector<Vec3>& corners, const WeldOptions& options = {});

// Throws Error(where) when the mesh has no triangle of positive area (none, or every one degenerate): there is
// no surface to plan on or to segment, only points and lines.
void check_has_area(const Mesh& mesh, const std::string& where);

// Builds a mesh from corners (3 per triangle). Degenerate triangles are kept (zero area, zero normal) so that
// reports can count them; consumers skip faces whose area is zero.
Mesh build_mesh(const std::vector<Vec3>& corners, const WeldOptions& options = {});
// Builds a mesh from welded triangles (normals, areas, edges, box); throws Error when a face names a vertex
// that does not exist.
Mesh mesh_from_indexed(IndexedTriangles triangles);

}  // namespace rosmill::core
