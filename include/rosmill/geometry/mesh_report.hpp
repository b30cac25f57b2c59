// What a mesh is made of and what is wrong with it: the `rosmill info` report.
#pragma once
#include <cstddef>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core {

struct MeshReport {
  size_t triangles = 0;
  size_t vertices = 0;
  Box3 bbox;
  double area = 0.0;
  bool closed = false;
  double volume = 0.0;  // signed-volume sum; meaningful only when closed
  size_t open_edges = 0;
  size_t nonmanifold_edges = 0;
  size_t degenerate = 0;
  size_t inconsistent_edges = 0;  // manifold edges whose two faces run in the same direction
};

MeshReport report(const Mesh& mesh);

// The same report, bit for bit, straight from welded triangles: no normals, areas or adjacency are kept, only
// one array of half-edges grouped by vertex (a fraction of the memory of a Mesh). Throws like mesh_from_indexed().
MeshReport report(const IndexedTriangles& triangles);

}  // namespace rosmill::core
