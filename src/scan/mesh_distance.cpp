#include "rosmill/scan/mesh_distance.hpp"

#include <algorithm>
#include <cmath>

#include <nanoflann.hpp>
#include <tbb/parallel_for.h>

#include "rosmill/error.hpp"

namespace rosmill::core::scan {

// The closest point by the Voronoi regions of the triangle's corners, edges and face (Ericson, "Real-Time
// Collision Detection", section 5.1.5): barycentric tests, no square roots.
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

struct MeshDistance::Index {
  std::vector<Vec3> points;
  std::vector<uint32_t> faces;
  size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(size_t i, size_t d) const { return points[i][int(d)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Index>, Index, 3, size_t>;
  std::unique_ptr<Tree> tree;
};

namespace {

// The cover: about the median edge, so a typical face has one index point, and no more than ~2e6 index points
// over the whole surface for a mesh of few large faces.
double choose_cover(const Mesh& mesh) {
  std::vector<double> edges;
  double area = 0;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    if (!(mesh.areas[f] > 0)) continue;
    area += mesh.areas[f];
    edges.push_back((mesh.corner(f, 1) - mesh.corner(f, 0)).norm());
  }
  std::nth_element(edges.begin(), edges.begin() + edges.size() / 2, edges.end());
  return std::max({edges[edges.size() / 2], std::sqrt(area / 2e6), 1e-6});
}

}  // namespace

MeshDistance::MeshDistance(const Mesh& mesh) : mesh_(mesh), index_(std::make_unique<Index>()) {
  check_has_area(mesh, "mesh distance");
  cover_ = choose_cover(mesh);
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    if (!(mesh.areas[f] > 0)) continue;
    const Vec3 &a = mesh.corner(f, 0), &b = mesh.corner(f, 1), &c = mesh.corner(f, 2);
    const Vec3 centre = (a + b + c) / 3.0;
    const double reach = std::max({(a - centre).norm(), (b - centre).norm(), (c - centre).norm()});
    // n steps along each edge: every point of the face lies within (longest edge / n) of a grid point.
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int n = reach <= cover_ ? 0 : int(std::ceil(longest / cover_));
    if (n == 0) {
      index_->points.push_back(centre);
      index_->faces.push_back(uint32_t(f));
      continue;
    }
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        index_->points.push_back(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n));
        index_->faces.push_back(uint32_t(f));
      }
  }
  index_->tree = std::make_unique<Index::Tree>(3, *index_, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  index_->tree->buildIndex();
}

MeshDistance::~MeshDistance() = default;

SurfaceDistance MeshDistance::query(const Vec3& p) const {
  size_t nearest = 0;
  double nearest_sq = 0;
  index_->tree->knnSearch(p.data(), 1, &nearest, &nearest_sq);
  const double reach = std::sqrt(nearest_sq) + cover_;
  std::vector<std::pair<size_t, double>> found;
  index_->tree->radiusSearch(p.data(), reach * reach * (1 + 1e-12), found, nanoflann::SearchParams(32, 0, false));
  SurfaceDistance best;
  double best_sq = std::numeric_limits<double>::infinity(), best_alignment = -1;
  uint32_t last_face = kNone;
  for (const auto& [i, unused] : found) {
    const uint32_t f = index_->faces[i];
    if (f == last_face) continue;  // a grid's points come in a row
    last_face = f;
    const Vec3 q = closest_on_triangle(p, mesh_.corner(f, 0), mesh_.corner(f, 1), mesh_.corner(f, 2));
    const Vec3 d = p - q;
    const double sq = d.squaredNorm();
    // At an edge or corner several faces share the nearest point: the sign comes from the face whose normal
    // lines up best with the way to the point (for a convex edge both agree; the choice matters at a concave one).
    const double alignment = sq > 0 ? std::abs(mesh_.normals[f].dot(d)) / std::sqrt(sq) : 1.0;
    if (sq < best_sq * (1 - 1e-9) || (sq <= best_sq * (1 + 1e-9) && alignment > best_alignment)) {
      best_sq = std::min(sq, best_sq);
      best_alignment = alignment;
      best.closest = q;
      best.face = f;
    }
  }
  const double dist = std::sqrt(best_sq);
  best.signed_distance = mesh_.normals[best.face].dot(p - best.closest) < 0 ? -dist : dist;
  return best;
}

std::vector<double> MeshDistance::distances(const std::vector<Vec3>& points) const {
  std::vector<double> out(points.size());
  tbb::parallel_for(size_t(0), points.size(), [&](size_t i) { out[i] = std::abs(query(points[i]).signed_distance); });
  return out;
}

}  // namespace rosmill::core::scan
