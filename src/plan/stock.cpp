#include "rosmill/plan/stock.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/slice/slicer.hpp"

namespace rosmill::core {
namespace {

// Sections are taken at most this far apart within a slab (mm).
constexpr double kSectionStep = 1.0;

// Crossings of the vertical ray from (x, y, z) with the mesh, above and below z.
std::pair<int, int> ray_crossings(const Mesh& mesh, double x, double y, double z) {
  int up = 0, down = 0;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const Vec3 &a = mesh.corner(f, 0), &b = mesh.corner(f, 1), &c = mesh.corner(f, 2);
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (det == 0) continue;  // vertical face: a vertical ray never crosses it
    const double u = ((x - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (y - a.y())) / det;
    const double v = ((b.x() - a.x()) * (y - a.y()) - (x - a.x()) * (b.y() - a.y())) / det;
    if (u < 0 || v < 0 || u + v > 1) continue;
    const double zh = a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
    if (zh > z) ++up;
    else if (zh < z) ++down;
  }
  return {up, down};
}

}  // namespace

bool inside_closed_mesh(const Mesh& mesh, const Vec3& p) {
  // The ray is moved off the exact point by a few micrometres in an odd direction, so that it does not run
  // through the mesh's edges and vertices (which lie on round numbers in most files). A point on the top or
  // bottom face has one crossing on the other side; a point on a wall is tried from four sides.
  for (const Vec2& off : {Vec2(1.2345e-6, 2.7183e-6), Vec2(-2.7183e-6, 1.2345e-6), Vec2(-1.2345e-6, -2.7183e-6),
                         Vec2(2.7183e-6, -1.2345e-6)}) {
    const auto [up, down] = ray_crossings(mesh, p.x() + off.x(), p.y() + off.y(), p.z());
    if (up % 2 == 1 || down % 2 == 1) return true;
  }
  return false;
}

void check_stock_mesh(const Mesh& stock, const Mesh* part) {
  if (stock.face_count() == 0) throw Error("stock", "the stock mesh has no triangles");
  if (!stock.closed()) {
    size_t open = 0;
    for (const MeshEdge& e : stock.edges) open += e.face_count != 2;
    throw Error("stock", "the stock mesh is not closed (" + std::to_string(open) +
                             " edges without exactly two faces): it bounds no volume to rough from");
  }
  if (!part || part->vertices.empty()) return;
  const double slack = 1e-6;
  const Box3& s = stock.bbox;
  const Box3& b = part->bbox;
  for (int k = 0; k < 3; ++k)
    if (b.min[k] < s.min[k] - slack || b.max[k] > s.max[k] + slack)
      throw Error("stock", "the stock mesh does not contain the part: the part's bounding box leaves the stock's "
                           "along " + std::string(1, "xyz"[k]));
  const size_t n = part->vertices.size(), stride = std::max<size_t>(1, n / 2000);
  std::atomic<size_t> outside{n};
  for_each_index(size_t(0), (n + stride - 1) / stride, [&](size_t i) {
    if (outside.load() != n) return;
    if (!inside_closed_mesh(stock, part->vertices[i * stride])) outside = i * stride;
  });
  if (outside != n) {
    const Vec3& v = part->vertices[outside];
    std::ostringstream s;
    s << "the stock mesh does not contain the part: the part's vertex (" << v.x() << ", " << v.y() << ", " << v.z()
      << ") lies outside it";
    throw Error("stock", s.str());
  }
}

StockReach::StockReach(const Mesh& stock, const std::vector<double>& levels, double top, double radius,
                       double arc_tolerance) {
  // Every section height of every slab, sliced in one go.
  std::vector<std::vector<double>> heights(levels.size());
  std::vector<double> planes;
  double above = top;
  for (size_t i = 0; i < levels.size(); ++i) {
    const double z = levels[i];
    const int n = std::max(1, static_cast<int>(std::ceil((above - z) / kSectionStep)));
    for (int k = 0; k <= n; ++k) heights[i].push_back(z + (above - z) * k / n);
    planes.insert(planes.end(), heights[i].begin(), heights[i].end());
    above = z;
  }
  std::sort(planes.begin(), planes.end());
  planes.erase(std::unique(planes.begin(), planes.end()), planes.end());
  const std::vector<SliceLayer> layers = slice_mesh(stock, planes);
  auto section = [&](double z) -> const std::vector<Contour>& {
    return layers[std::lower_bound(planes.begin(), planes.end(), z) - planes.begin()].contours;
  };
  // Grown by the radius plus the arc tolerance: Clipper's round joins are chords inside the true arcs, so the
  // loops then hold every point within the radius of material.
  loops_.resize(levels.size());
  for_each_index(size_t(0), levels.size(), [&](size_t i) {
    std::vector<Contour> slab;
    for (double z : heights[i]) slab = union_regions(slab, section(z));
    loops_[i] = offset_region(slab, radius + arc_tolerance, arc_tolerance);
  });
}

std::vector<std::pair<double, double>> StockReach::along(size_t level, const Vec2& origin, const Vec2& dir,
                                                         double len) const {
  // Crossings of the line with every loop; the loops do not overlap, so inside is an odd count (even-odd). A
  // vertex on the line counts on the positive side only, so a line through it crosses once or not at all.
  std::vector<double> s;
  auto side = [&](const Vec2& p) { return dir.x() * (p.y() - origin.y()) - dir.y() * (p.x() - origin.x()); };
  for (const OffsetLoop& loop : loops_.at(level)) {
    const auto& pts = loop.points;
    for (size_t k = 0; k < pts.size(); ++k) {
      const Vec2 &p = pts[k], &q = pts[(k + 1) % pts.size()];
      const double sp = side(p), sq = side(q);
      if ((sp > 0) == (sq > 0)) continue;
      const Vec2 x = p + (q - p) * (sp / (sp - sq));
      s.push_back((x - origin).dot(dir));
    }
  }
  std::sort(s.begin(), s.end());
  std::vector<std::pair<double, double>> out;
  for (size_t k = 0; k + 1 < s.size(); k += 2) {
    const double a = std::max(0.0, s[k]), b = std::min(len, s[k + 1]);
    if (a < b) out.emplace_back(a, b);
  }
  return out;
}

std::vector<std::pair<double, double>> intersect_spans(const std::vector<std::pair<double, double>>& spans,
                                                       const std::vector<std::pair<double, double>>& keep) {
  std::vector<std::pair<double, double>> out;
  size_t j = 0;
  for (const auto& [a, b] : spans) {
    while (j < keep.size() && keep[j].second <= a) ++j;
    for (size_t k = j; k < keep.size() && keep[k].first < b; ++k) {
      const double lo = std::max(a, keep[k].first), hi = std::min(b, keep[k].second);
      if (lo < hi) out.emplace_back(lo, hi);
    }
  }
  return out;
}

}  // namespace rosmill::core
