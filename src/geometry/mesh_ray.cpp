#include "rosmill/geometry/mesh_ray.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rosmill/geometry/sphere_sweep.hpp"

namespace rosmill::core {
namespace {

constexpr uint32_t kLeafFacets = 8;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The ray's parameter range inside a box (slab test), empty when t0 > t1.
bool through_box(const double* lo, const double* hi, const Vec3& o, const Vec3& inv, double& t0, double& t1) {
  for (int a = 0; a < 3; ++a) {
    double n = (lo[a] - o[a]) * inv[a], f = (hi[a] - o[a]) * inv[a];
    if (std::isnan(n)) n = -kInf;  // a ray in the slab's plane (0 * inf): inside along this axis
    if (std::isnan(f)) f = kInf;
    if (n > f) std::swap(n, f);
    t0 = std::max(t0, n);
    t1 = std::min(t1, f);
  }
  return t0 <= t1;
}

// Moller-Trumbore: the ray's parameter at the triangle, +infinity when it misses.
double triangle_hit(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& o, const Vec3& d) {
  const Vec3 e1 = b - a, e2 = c - a, p = d.cross(e2);
  const double det = e1.dot(p);
  if (det == 0) return kInf;  // the ray runs in the triangle's plane
  const double inv = 1.0 / det;
  const Vec3 s = o - a;
  const double u = s.dot(p) * inv;
  if (u < 0 || u > 1) return kInf;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) * inv;
  if (v < 0 || u + v > 1) return kInf;
  return e2.dot(q) * inv;
}

}  // namespace

MeshRays::MeshRays(const Mesh& mesh) : mesh_(mesh) {
  const uint32_t n = static_cast<uint32_t>(mesh.face_count());
  std::vector<Vec3> centroids(n);
  order_.resize(n);
  for (uint32_t f = 0; f < n; ++f) {
    centroids[f] = (mesh.corner(f, 0) + mesh.corner(f, 1) + mesh.corner(f, 2)) / 3.0;
    order_[f] = f;
  }
  nodes_.reserve(2 * (n / kLeafFacets + 1));
  if (n > 0) build(0, n, centroids);
}

uint32_t MeshRays::build(uint32_t begin, uint32_t end, const std::vector<Vec3>& centroids) {
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Box3 box, centres;
  for (uint32_t k = begin; k < end; ++k) {
    for (int i = 0; i < 3; ++i) box.add(mesh_.corner(order_[k], i));
    centres.add(centroids[order_[k]]);
  }
  for (int a = 0; a < 3; ++a) nodes_[index].lo[a] = box.min[a], nodes_[index].hi[a] = box.max[a];
  if (end - begin <= kLeafFacets) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  int axis = 0;
  centres.size().maxCoeff(&axis);
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](uint32_t x, uint32_t y) { return centroids[x][axis] < centroids[y][axis]; });
  build(begin, mid, centroids);
  const uint32_t right = build(mid, end, centroids);
  nodes_[index].first = right;
  return index;
}

// The hierarchy walked along a ray, each node's box grown by `grow`: `leaf(facet, best)` gives the parameter at
// which the ray meets a facet (+infinity for none); the least over the facets met, boxes beyond it skipped.
template <class Leaf>
double MeshRays::walk(const Vec3& o, const Vec3& d, double grow, double t_min, double t_max, Leaf&& leaf) const {
  if (nodes_.empty()) return kInf;
  const Vec3 inv(1.0 / d.x(), 1.0 / d.y(), 1.0 / d.z());
  double best = kInf;
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) lo[a] = node.lo[a] - grow, hi[a] = node.hi[a] + grow;
    double t0 = t_min, t1 = std::min(t_max, best);
    if (!through_box(lo, hi, o, inv, t0, t1)) continue;
    if (node.count > 0) {
      for (uint32_t k = node.first; k < node.first + node.count; ++k) best = std::min(best, leaf(order_[k], best));
      if (best == t_min) return best;  // nothing comes before the start
      continue;
    }
    const uint32_t self = static_cast<uint32_t>(&node - nodes_.data());
    stack[top++] = node.first;  // the right child, visited after the left
    stack[top++] = self + 1;
  }
  return best;
}

double MeshRays::first_hit(const Vec3& o, const Vec3& d, double t_min, double t_max, uint32_t* face) const {
  return walk(o, d, 0.0, t_min, t_max, [&](uint32_t f, double best) {
    const double t = triangle_hit(mesh_.corner(f, 0), mesh_.corner(f, 1), mesh_.corner(f, 2), o, d);
    if (!(t > t_min && t <= t_max && t < best)) return kInf;
    if (face) *face = f;
    return t;
  });
}

double MeshRays::first_sphere_contact(const Vec3& o, const Vec3& d, double radius, double t_min, double t_max) const {
  // A box grown by the radius holds every centre that touches one of its facets.
  return walk(o, d, radius, t_min, t_max, [&](uint32_t f, double best) {
    return sphere_sweep_triangle(o, d, radius, mesh_.corner(f, 0), mesh_.corner(f, 1), mesh_.corner(f, 2), t_min,
                                 std::min(t_max, best));
  });
}

}  // namespace rosmill::core
