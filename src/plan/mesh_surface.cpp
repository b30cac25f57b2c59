#include "rosmill/plan/mesh_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "rosmill/parallel.hpp"

namespace rosmill::core {
namespace {

constexpr uint32_t kLeafSize = 4;
constexpr double kNoStop = std::numeric_limits<double>::infinity();

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

// Squared horizontal distance from (x, y) to an XY box (a tree node's or a triangle's).
template <class Box>
double box_distance_sq(const Box& b, double x, double y) {
  const double dx = std::max({0.0, b.xmin - x, x - b.xmax});
  const double dy = std::max({0.0, b.ymin - y, y - b.ymax});
  return dx * dx + dy * dy;
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
  for_each_index(size_t(0), n, [&](size_t f) {
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
  for_each_index(size_t(0), n, [&](size_t i) {
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

// Branch and bound from `best` up: returns the highest contact above `best` (or `best` when none is), stopping
// at the first one above `enough`. A drop starts from nothing and never stops early; the question "is the tip
// held above z?" starts from z itself, so that every box whose highest point cannot lift the cutter above z is
// never opened, and stops at the first triangle that does.
double MeshSurface::highest_contact(const CutterProfile& cp, double x, double y, double best, double enough,
                                    uint32_t& hint) const {
  uint32_t winner = hint;
  if (hint < tris_.size()) {
    const double z = triangle_contact(cp, x, y, tris_[hint]);
    if (z > best) best = z;
    if (best > enough) return best;
  }
  if (nodes_.empty()) return best;

  // Upper bound of any contact inside a box: its top minus the cutter's height at the nearest distance. Boxes
  // and triangles are culled by the same reach as the contacts themselves.
  const double reach2 = cp.reach_sq(x, y);
  auto bound = [&](const Node& nd) {
    const double d2 = box_distance_sq(nd, x, y);
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
        const double d2 = box_distance_sq(t, x, y);
        if (d2 > reach2 || t.zmax - cp.height_sq(std::min(d2, cp.R2)) <= best) continue;
        const double z = triangle_contact(cp, x, y, t);
        if (z > best) best = z, winner = i;
      }
      if (best > enough) break;
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
  return best;
}

Drop MeshSurface::drop_hinted(const CutterProfile& cp, double x, double y, uint32_t& hint) const {
  const double best = highest_contact(cp, x, y, kNoContact, kNoStop, hint);
  if (best == kNoContact) return {bounds_.min.z(), false};
  return {best, true};
}

bool MeshSurface::held_above_hinted(const CutterProfile& cp, double x, double y, double z, uint32_t& hint) const {
  return highest_contact(cp, x, y, z, z, hint) > z;
}

// The probe of a mesh: at each focus, the triangles whose box lies within the cutter's reach of some point of the
// focus disc and whose top, less the cutter's height at their nearest possible distance, is above z (one walk of
// the tree); a question then runs the culls and the contact over those, as the tree's leaves would.
class MeshLevelProbe : public LevelProbe {
 public:
  MeshLevelProbe(const MeshSurface& mesh, const Cutter& cutter, double z) : m_(mesh), cp_(cutter), z_(z) {}

  void focus(const Vec2& centre, double radius) override {
    near_.clear();
    if (m_.nodes_.empty()) return;
    const double x = centre.x(), y = centre.y();
    radius = radius * (1 + 1e-9) + 1e-9;  // a question a rounding beyond the disc is still answered in full
    // The widest reach of any question in the disc (reach_sq grows with the coordinates' size).
    const double reach = radius + std::sqrt(cp_.reach_sq(std::abs(x) + radius, std::abs(y) + radius));
    auto bound = [&](const auto& b) {
      const double d2 = box_distance_sq(b, x, y);
      if (d2 > reach * reach) return kNoContact;
      const double near = std::max(0.0, std::sqrt(d2) - radius);
      return b.zmax - cp_.height_sq(std::min(near * near, cp_.R2));
    };
    uint32_t stack[128];
    int top = 0;
    if (bound(m_.nodes_[0]) > z_) stack[top++] = 0;
    while (top > 0) {
      const uint32_t id = stack[--top];
      const MeshSurface::Node& nd = m_.nodes_[id];
      if (nd.count > 0) {
        for (uint32_t i = nd.first; i < nd.first + nd.count; ++i)
          if (bound(m_.tris_[i]) > z_) near_.push_back(i);
        continue;
      }
      const uint32_t l = id + 1, r = nd.first;
      if (bound(m_.nodes_[r]) > z_) stack[top++] = r;
      if (bound(m_.nodes_[l]) > z_) stack[top++] = l;
    }
  }

  bool held_above(double x, double y) override {
    const double reach2 = cp_.reach_sq(x, y);
    for (size_t k = 0; k < near_.size(); ++k) {
      const ContactTriangle& t = m_.tris_[near_[k]];
      const double d2 = box_distance_sq(t, x, y);
      if (d2 > reach2 || t.zmax - cp_.height_sq(std::min(d2, cp_.R2)) <= z_) continue;
      if (triangle_contact(cp_, x, y, t) > z_) {
        std::swap(near_[0], near_[k]);  // the next question, close by, is likely held by the same triangle
        return true;
      }
    }
    return false;
  }

 private:
  const MeshSurface& m_;
  CutterProfile cp_;
  double z_;
  std::vector<uint32_t> near_;
};

std::unique_ptr<LevelProbe> MeshSurface::level_probe(const Cutter& cutter, double z) const {
  return std::make_unique<MeshLevelProbe>(*this, cutter, z);
}

bool MeshSurface::held_above(const Cutter& cutter, double x, double y, double z) const {
  uint32_t hint = kNone;
  return held_above_hinted(CutterProfile(cutter), x, y, z, hint);
}

Drop MeshSurface::drop(const Cutter& cutter, double x, double y) const {
  uint32_t hint = kNone;
  return drop_hinted(CutterProfile(cutter), x, y, hint);
}

void MeshSurface::drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const {
  const CutterProfile cp(cutter);
  for_each_piece<size_t>(0, n, 256, [&](size_t begin, size_t end) {
    uint32_t hint = kNone;
    for (size_t i = begin; i != end; ++i) out[i] = drop_hinted(cp, xy[i].x(), xy[i].y(), hint);
  });
}

}  // namespace rosmill::core
