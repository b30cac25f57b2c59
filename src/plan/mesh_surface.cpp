#include "rosmill/plan/mesh_surface.hpp"

#include <algorithm>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace rosmill::core {
namespace {

constexpr uint32_t kLeafSize = 4;

// Which corners and edges each face tests: a shared corner or edge is tested by one face only.
std::vector<unsigned char> ownership(const Mesh& mesh) {
  std::vector<unsigned char> own(mesh.face_count(), 0);
  std::vector<char> vertex_taken(mesh.vertex_count(), 0);
  for (size_t f = 0; f < mesh.face_count(); ++f)
    for (int i = 0; i < 3; ++i) {
      const uint32_t v = mesh.faces[f][i];
      if (!vertex_taken[v]) vertex_taken[v] = 1, own[f] |= 1u << i;
      const bool has_edges = mesh.face_edges.size() == mesh.face_count() && !mesh.edges.empty();
      if (!has_edges) {
        own[f] |= 8u << i;
        continue;
      }
      const MeshEdge& e = mesh.edges[mesh.face_edges[f][i]];
      if (e.face_count == 0 || mesh.edge_faces[e.first_face] == f) own[f] |= 8u << i;
    }
  return own;
}

}  // namespace

MeshSurface::MeshSurface(const Mesh& mesh) : bounds_(mesh.bbox) {
  const size_t n = mesh.face_count();
  if (bounds_.empty())
    for (const Vec3& v : mesh.vertices) bounds_.add(v);
  if (n == 0) return;
  // The tree is built over a permutation of compact face boxes; the (large) contact records are then made once,
  // directly in leaf order, on both cores.
  std::vector<FaceBox> boxes(n);
  tbb::parallel_for(size_t(0), n, [&](size_t f) {
    const Vec3 &a = mesh.corner(f, 0), &b = mesh.corner(f, 1), &c = mesh.corner(f, 2);
    boxes[f] = {std::min({a.x(), b.x(), c.x()}), std::max({a.x(), b.x(), c.x()}), std::min({a.y(), b.y(), c.y()}),
                std::max({a.y(), b.y(), c.y()}), std::max({a.z(), b.z(), c.z()})};
  });
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  nodes_.reserve(2 * n / kLeafSize + 2);
  nodes_.push_back({});
  build(0, 0, static_cast<uint32_t>(n), boxes, order);
  const std::vector<unsigned char> own = ownership(mesh);
  tris_.resize(n);
  tbb::parallel_for(size_t(0), n, [&](size_t i) {
    const uint32_t f = order[i];
    tris_[i] = make_contact_triangle(mesh.corner(f, 0).data(), mesh.corner(f, 1).data(), mesh.corner(f, 2).data(),
                                     own[f]);
  });
}

// Median split on the longer side of the centres' extent (centre of each face's XY box), so that a leaf is one
// contiguous run of `order` and so of tris_ (cache-friendly queries).
void MeshSurface::build(uint32_t node, uint32_t begin, uint32_t end, const std::vector<FaceBox>& boxes,
                        std::vector<uint32_t>& order) {
  Node nd{1e300, 1e300, -1e300, -1e300, -1e300, begin, end - begin};
  double cxmin = 1e300, cxmax = -1e300, cymin = 1e300, cymax = -1e300;
  for (uint32_t i = begin; i < end; ++i) {
    const FaceBox& b = boxes[order[i]];
    nd.xmin = std::min(nd.xmin, b.xmin), nd.xmax = std::max(nd.xmax, b.xmax);
    nd.ymin = std::min(nd.ymin, b.ymin), nd.ymax = std::max(nd.ymax, b.ymax);
    nd.zmax = std::max(nd.zmax, b.zmax);
    const double cx = b.xmin + b.xmax, cy = b.ymin + b.ymax;  // twice the centre: only the order matters
    cxmin = std::min(cxmin, cx), cxmax = std::max(cxmax, cx);
    cymin = std::min(cymin, cy), cymax = std::max(cymax, cy);
  }
  if (end - begin <= kLeafSize) {
    nodes_[node] = nd;
    return;
  }
  const bool split_x = cxmax - cxmin >= cymax - cymin;
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end, [&](uint32_t a, uint32_t b) {
    const FaceBox &ba = boxes[a], &bb = boxes[b];
    return split_x ? ba.xmin + ba.xmax < bb.xmin + bb.xmax : ba.ymin + ba.ymax < bb.ymin + bb.ymax;
  });

  nd.count = 0;
  nodes_[node] = nd;
  const uint32_t left = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back({});
  build(left, begin, mid, boxes, order);
  const uint32_t right = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back({});
  nodes_[node].first = right;
  build(right, mid, end, boxes, order);
}

Drop MeshSurface::drop_hinted(const CutterProfile& cp, double x, double y, uint32_t& hint) const {
  double best = kNoContact;
  uint32_t winner = hint;
  if (hint < tris_.size()) best = triangle_contact(cp, x, y, tris_[hint]);
  if (nodes_.empty()) return {bounds_.min.z(), false};

  // Upper bound of any contact inside a box: its top minus the cutter's height at the nearest distance. Boxes
  // and triangles are culled by the same reach as the contacts themselves.
  const double reach2 = cp.reach_sq(x, y);
  auto bound = [&](const Node& nd) {
    const double dx = std::max({0.0, nd.xmin - x, x - nd.xmax});
    const double dy = std::max({0.0, nd.ymin - y, y - nd.ymax});
    const double d2 = dx * dx + dy * dy;
    if (d2 > reach2) return kNoContact;
    return nd.zmax - cp.height_sq(std::min(d2, cp.R2));
  };
  struct Entry {
    uint32_t node;
    double ub;
  };
  Entry stack[128];
  int top = 0;
  const double ub0 = bound(nodes_[0]);
  if (ub0 > best) stack[top++] = {0, ub0};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.ub <= best) continue;
    const Node& nd = nodes_[e.node];
    if (nd.count > 0) {
      for (uint32_t i = nd.first; i < nd.first + nd.count; ++i) {
        const ContactTriangle& t = tris_[i];
        if (t.zmax <= best) continue;
        const double dx = std::max({0.0, t.xmin - x, x - t.xmax});
        const double dy = std::max({0.0, t.ymin - y, y - t.ymax});
        const double d2 = dx * dx + dy * dy;
        if (d2 > reach2 || t.zmax - cp.height_sq(std::min(d2, cp.R2)) <= best) continue;
        const double z = triangle_contact(cp, x, y, t);
        if (z > best) best = z, winner = i;
      }
      continue;
    }
    const uint32_t l = e.node + 1, r = nd.first;
    const double ubl = bound(nodes_[l]), ubr = bound(nodes_[r]);
    // The more promising child is searched first (pushed last) so that the bound rises early.
    if (ubl > ubr) {
      if (ubr > best) stack[top++] = {r, ubr};
      if (ubl > best) stack[top++] = {l, ubl};
    } else {
      if (ubl > best) stack[top++] = {l, ubl};
      if (ubr > best) stack[top++] = {r, ubr};
    }
  }
  hint = winner;
  if (best == kNoContact) return {bounds_.min.z(), false};
  return {best, true};
}

Drop MeshSurface::drop(const Cutter& cutter, double x, double y) const {
  uint32_t hint = kNone;
  return drop_hinted(CutterProfile(cutter), x, y, hint);
}

void MeshSurface::drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const {
  const CutterProfile cp(cutter);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& range) {
    uint32_t hint = kNone;
    for (size_t i = range.begin(); i != range.end(); ++i) out[i] = drop_hinted(cp, xy[i].x(), xy[i].y(), hint);
  });
}

}  // namespace rosmill::core
