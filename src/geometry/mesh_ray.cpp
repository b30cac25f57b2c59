#include "rosmill/geometry/mesh_ray.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rosmill/geometry/sphere_sweep.hpp"

namespace rosmill::core {
namespace {

constexpr uint32_t kLeafFacets = 8;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The ray's parameter range inside a box (slab test), empty when t0 > t1. A ray parallel to a slab (d zero along
// its axis, of either sign: -0 turns 1 / d into -infinity) is inside it or not at all, whatever t: decided by the
// origin alone, so that a ray along a box's face (a raster line over a symmetric part's middle) is not lost.
bool through_box(const double* lo, const double* hi, const Vec3& o, const Vec3& d, const Vec3& inv, double& t0,
                 double& t1) {
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double n = (lo[a] - o[a]) * inv[a], f = (hi[a] - o[a]) * inv[a];
    if (n > f) std::swap(n, f);
    t0 = std::max(t0, n);
    t1 = std::min(t1, f);
  }
  return t0 <= t1;
}

// The ray's parameter at the triangle, +infinity when it misses: Woop, Benthin and Wald's "Watertight Ray/Triangle
// Intersection" (JCGT 2013). The corners are sheared into a frame where the ray runs along +z through the origin;
// the signed areas the ray makes with each edge are then the same products for the two facets that share the edge,
// negated, so a ray through an edge or a corner of a closed mesh meets at least one of its facets (Moller and
// Trumbore's test can miss both where rounding puts it a hair outside each).
double triangle_hit(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& o, const Vec3& d) {
  int kz = 0;
  d.cwiseAbs().maxCoeff(&kz);
  if (!(d[kz] != 0)) return kInf;  // no direction
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (d[kz] < 0) std::swap(kx, ky);  // keeps the corners' winding
  const double sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1.0 / d[kz];
  const Vec3 pa = a - o, pb = b - o, pc = c - o;
  const double ax = pa[kx] - sx * pa[kz], ay = pa[ky] - sy * pa[kz];
  const double bx = pb[kx] - sx * pb[kz], by = pb[ky] - sy * pb[kz];
  const double cx = pc[kx] - sx * pc[kz], cy = pc[ky] - sy * pc[kz];
  double u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
  if (u == 0 || v == 0 || w == 0) {  // on an edge to double precision: decided in extended precision
    using L = long double;
    u = double(L(cx) * L(by) - L(cy) * L(bx));
    v = double(L(ax) * L(cy) - L(ay) * L(cx));
    w = double(L(bx) * L(ay) - L(by) * L(ax));
  }
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return kInf;
  const double det = u + v + w;
  if (det == 0) return kInf;  // the ray runs in the triangle's plane
  const double t = (u * sz * pa[kz] + v * sz * pb[kz] + w * sz * pc[kz]) / det;
  return std::isfinite(t) ? t : kInf;
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
    if (!through_box(lo, hi, o, d, inv, t0, t1)) continue;
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
