#include "rosmill/geometry/mesh_report.hpp"

#include <Eigen/Geometry>

namespace rosmill::core {

MeshReport report(const Mesh& mesh) {
  MeshReport r;
  r.triangles = mesh.faces.size();
  r.vertices = mesh.vertices.size();
  r.bbox = mesh.bbox;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    r.area += mesh.areas[f];
    if (mesh.areas[f] == 0.0) ++r.degenerate;
  }
  for (const MeshEdge& e : mesh.edges) {
    if (e.boundary()) ++r.open_edges;
    if (e.nonmanifold()) ++r.nonmanifold_edges;
    if (e.manifold() && !e.consistent) ++r.inconsistent_edges;
  }
  r.closed = mesh.closed();
  // Divergence theorem: sum of signed tetrahedra against the bbox centre (centring keeps the sum accurate).
  const Vec3 c = r.bbox.empty() ? Vec3::Zero() : Vec3(0.5 * (r.bbox.min + r.bbox.max));
  double six_v = 0.0;
  for (const auto& t : mesh.faces) {
    const Vec3 a = mesh.vertices[t[0]] - c, b = mesh.vertices[t[1]] - c, d = mesh.vertices[t[2]] - c;
    six_v += a.dot(b.cross(d));
  }
  r.volume = six_v / 6.0;
  return r;
}

}  // namespace rosmill::core
