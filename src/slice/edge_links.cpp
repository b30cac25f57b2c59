#include "edge_links.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include <cmath>

#include "rosmill/parallel.hpp"

namespace rosmill::core::slice_detail {
namespace {

struct Fan {
  uint32_t half_edge;
  double angle;
  bool forward;  // the face runs the edge from e.a to e.b
};

// Half-edges of edge `e`, one per entry of its face list (a folded degenerate face may use an edge twice).
void collect_half_edges(const Mesh& mesh, uint32_t e, std::vector<uint32_t>& out) {
  out.clear();
  const MeshEdge& edge = mesh.edges[e];
  for (uint32_t k = 0; k < edge.face_count; ++k) {
    const uint32_t f = mesh.edge_faces[edge.first_face + k];
    for (uint32_t j = 0; j < 3; ++j) {
      const uint32_t h = 3 * f + j;
      if (mesh.face_edges[f][j] == e && std::find(out.begin(), out.end(), h) == out.end()) {
        out.push_back(h);
        break;
      }
    }
  }
}

void pair_fan(const Mesh& mesh, const MeshEdge& edge, const std::vector<uint32_t>& half, std::vector<uint32_t>& links,
              std::vector<Fan>& fan) {
  const Vec3& a = mesh.vertices[edge.a];
  const Vec3 u = (mesh.vertices[edge.b] - a).normalized();
  // Any frame (x, y) perpendicular to the edge measures the angle of each face around it.
  const Vec3 axis = std::abs(u.x()) < 0.9 ? Vec3(Vec3::UnitX()) : Vec3(Vec3::UnitY());
  const Vec3 x = axis.cross(u).normalized();
  const Vec3 y = u.cross(x);
  fan.clear();
  for (uint32_t h : half) {
    const uint32_t f = h / 3, j = h % 3;
    const Vec3 w = mesh.vertices[mesh.faces[f][(j + 2) % 3]] - a;
    fan.push_back({h, std::atan2(w.dot(y), w.dot(x)), mesh.faces[f][j] == edge.a});
  }
  std::sort(fan.begin(), fan.end(), [](const Fan& l, const Fan& r) { return l.angle < r.angle; });
  const size_t k = fan.size();
  // A forward face's normal (u x w) points towards increasing angle, so material lies on its decreasing side:
  // the wedge from a backward face to the next (forward) face is material.
  bool alternates = k % 2 == 0;
  for (size_t i = 0; alternates && i < k; ++i) alternates = fan[i].forward != fan[(i + 1) % k].forward;
  size_t offset = 0;
  if (alternates && fan[0].forward) offset = 1;
  for (size_t i = 0; i + 1 < k; i += 2) {
    const uint32_t p = fan[(offset + i) % k].half_edge, q = fan[(offset + i + 1) % k].half_edge;
    links[p] = q;
    links[q] = p;
  }
}

// Links of one manifold edge whose two faces differ; false when the edge needs the general fan pairing.
bool link_manifold(const Mesh& mesh, uint32_t e, std::vector<uint32_t>& links) {
  const MeshEdge& edge = mesh.edges[e];
  const uint32_t f0 = mesh.edge_faces[edge.first_face], f1 = mesh.edge_faces[edge.first_face + 1];
  if (f0 == f1) return false;
  uint32_t h0 = kNone, h1 = kNone;
  for (uint32_t j = 0; j < 3; ++j) {
    if (mesh.face_edges[f0][j] == e) h0 = 3 * f0 + j;
    if (mesh.face_edges[f1][j] == e) h1 = 3 * f1 + j;
  }
  links[h0] = h1;
  links[h1] = h0;
  return true;
}

}  // namespace

std::vector<uint32_t> build_edge_links(const Mesh& mesh) {
  std::vector<uint32_t> links(3 * mesh.faces.size(), kNone);
  // Each edge writes only its own half-edges' links, so edges are linked in parallel.
  for_each_piece<uint32_t>(0, uint32_t(mesh.edges.size()), 16384, [&](uint32_t begin, uint32_t end) {
    std::vector<uint32_t> half;
    std::vector<Fan> fan;
    for (uint32_t e = begin; e < end; ++e) {
      const MeshEdge& edge = mesh.edges[e];
      if (edge.a == edge.b || edge.face_count < 2) continue;
      if (edge.face_count == 2 && link_manifold(mesh, e, links)) continue;
      collect_half_edges(mesh, e, half);
      pair_fan(mesh, edge, half, links, fan);
    }
  });
  return links;
}

}  // namespace rosmill::core::slice_detail
