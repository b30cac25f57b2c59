#include "rosmill/scan/mesh_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nanoflann.hpp>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"

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

// One index point per piece of the face, split by longest-edge bisection (Rivara, "Algorithms for refining
// triangular grids suitable for adaptive and multigrid techniques", 1984) until each piece lies within `cover` of
// its centroid: a sliver gets a row of points along its length rather than a grid over its longest edge squared.
void cover_face(const Vec3& a, const Vec3& b, const Vec3& c, double cover, uint32_t face, std::vector<Vec3>& points,
                std::vector<uint32_t>& faces) {
  const Vec3 centre = (a + b + c) / 3.0;
  // The farthest point of a triangle from any point is one of its corners.
  if (std::max({(a - centre).norm(), (b - centre).norm(), (c - centre).norm()}) <= cover) {
    points.push_back(centre);
    faces.push_back(face);
    return;
  }
  const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(), ca = (a - c).squaredNorm();
  // The corners renamed so that (p, q) is the longest edge and r the corner across it.
  const bool on_ab = ab >= bc && ab >= ca, on_bc = !on_ab && bc >= ca;
  const Vec3& p = on_ab ? a : on_bc ? b : c;
  const Vec3& q = on_ab ? b : on_bc ? c : a;
  const Vec3& r = on_ab ? c : on_bc ? a : b;
  const Vec3 middle = (p + q) / 2.0;
  cover_face(p, middle, r, cover, face, points, faces);
  cover_face(middle, q, r, cover, face, points, faces);
}

}  // namespace

MeshDistance::MeshDistance(const Mesh& mesh) : mesh_(mesh), index_(std::make_unique<Index>()) {
  check_has_area(mesh, "mesh distance");
  cover_ = choose_cover(mesh);
  index_->points.reserve(mesh.face_count());
  index_->faces.reserve(mesh.face_count());
  for (size_t f = 0; f < mesh.face_count(); ++f)
    if (mesh.areas[f] > 0)
      cover_face(mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2), cover_, uint32_t(f), index_->points,
                 index_->faces);
  // nanoflann 1.4 builds the tree in its constructor.
  index_->tree = std::make_unique<Index::Tree>(3, *index_, nanoflann::KDTreeSingleIndexAdaptorParams(16));
}

MeshDistance::~MeshDistance() = default;

// nanoflann's result set for the nearest face: each index point the search meets brings its face, whose exact
// distance decides; the search reach is the best distance so far plus the cover (no face beyond it can be nearer),
// so the tree prunes more as the answer firms up, and a point farther than the limit costs only a short descent.
struct MeshDistance::NearestFace {
  NearestFace(const Mesh& m, const Index& i, const Vec3& point, double c, double reach)
      : mesh(m), index(i), p(point), cover(c), reach_sq(reach) {}
  const Mesh& mesh;
  const Index& index;
  Vec3 p;
  double cover;
  double reach_sq;  // the search radius, squared
  double best_sq = std::numeric_limits<double>::infinity(), best_alignment = -1;
  uint32_t last_face = kNone;
  SurfaceDistance best;
  bool found = false;

  double worstDist() const { return reach_sq; }
  bool full() const { return found; }
  bool addPoint(double, size_t i) {
    const uint32_t f = index.faces[i];
    if (f == last_face) return true;  // a grid's points come in a row
    last_face = f;
    const Vec3 q = closest_on_triangle(p, mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2));
    const Vec3 d = p - q;
    const double sq = d.squaredNorm();
    // At an edge or corner several faces share the nearest point: the sign comes from the face whose normal
    // lines up best with the way to the point (for a convex edge both agree; the choice matters at a concave one).
    const double alignment = sq > 0 ? std::abs(mesh.normals[f].dot(d)) / std::sqrt(sq) : 1.0;
    if (sq < best_sq * (1 - 1e-9) || (sq <= best_sq * (1 + 1e-9) && alignment > best_alignment)) {
      best_sq = std::min(sq, best_sq);
      best_alignment = alignment;
      best.closest = q;
      best.face = f;
      found = true;
      const double reach = std::sqrt(best_sq) + cover;
      reach_sq = std::min(reach_sq, reach * reach * (1 + 1e-12));
    }
    return true;
  }
};

bool MeshDistance::query_within(const Vec3& p, double limit, SurfaceDistance& out) const {
  const double reach = limit + cover_;
  NearestFace search(mesh_, *index_, p, cover_, std::isfinite(reach) ? reach * reach * (1 + 1e-12) : reach);
  index_->tree->findNeighbors(search, p.data(), nanoflann::SearchParams());
  if (!search.found || search.best_sq > limit * limit) return false;
  out = search.best;
  const double dist = std::sqrt(search.best_sq);
  out.signed_distance = mesh_.normals[out.face].dot(p - out.closest) < 0 ? -dist : dist;
  return true;
}

SurfaceDistance MeshDistance::query(const Vec3& p) const {
  SurfaceDistance out;
  query_within(p, std::numeric_limits<double>::infinity(), out);
  return out;
}

std::vector<double> MeshDistance::distances(const std::vector<Vec3>& points, double limit) const {
  std::vector<double> out(points.size());
  for_each_piece<size_t>(0, points.size(), 256, [&](size_t begin, size_t end) {
    SurfaceDistance s;
    for (size_t i = begin; i != end; ++i)
      out[i] = query_within(points[i], limit, s) ? std::abs(s.signed_distance)
                                                 : std::numeric_limits<double>::infinity();
  });
  return out;
}

}  // namespace rosmill::core::scan
