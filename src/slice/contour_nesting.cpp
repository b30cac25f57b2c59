#include "contour_nesting.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rosmill::core::slice_detail {
namespace {

struct Box2 {
  Vec2 min, max;
  bool contains(const Box2& o) const {
    return min.x() <= o.min.x() && min.y() <= o.min.y() && max.x() >= o.max.x() && max.y() >= o.max.y();
  }
};

Box2 box_of(const std::vector<Vec2>& pts) {
  Box2 b{pts[0], pts[0]};
  for (const Vec2& p : pts) {
    b.min = b.min.cwiseMin(p);
    b.max = b.max.cwiseMax(p);
  }
  return b;
}

// The midpoint of the longest segment: least likely to lie on a neighbouring contour that touches this one at
// a vertex.
Vec2 probe_point(const std::vector<Vec2>& pts) {
  size_t best = 0;
  double best_len = -1.0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const double len = (pts[(i + 1) % pts.size()] - pts[i]).squaredNorm();
    if (len > best_len) best_len = len, best = i;
  }
  return 0.5 * (pts[best] + pts[(best + 1) % pts.size()]);
}

}  // namespace

bool point_in_polygon(const Vec2& p, const std::vector<Vec2>& poly) {
  bool inside = false;
  const size_t n = poly.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

void orient_and_nest(std::vector<Contour>& contours) {
  std::vector<size_t> order;
  std::vector<double> signed_areas(contours.size(), 0.0);
  std::vector<Box2> boxes(contours.size());
  for (size_t i = 0; i < contours.size(); ++i) {
    Contour& c = contours[i];
    c.parent = -1;
    c.hole = false;
    if (!c.closed) {
      c.area = 0.0;
      continue;
    }
    signed_areas[i] = signed_area(c.points);
    c.area = std::abs(signed_areas[i]);
    boxes[i] = box_of(c.points);
    order.push_back(i);
  }
  // Larger first: a contour's enclosing contours all come before it, the nearest one last.
  std::stable_sort(order.begin(), order.end(), [&](size_t l, size_t r) { return contours[l].area > contours[r].area; });
  std::vector<int> depth(contours.size(), 0);
  for (size_t k = 0; k < order.size(); ++k) {
    const size_t i = order[k];
    const Vec2 probe = probe_point(contours[i].points);
    for (size_t m = k; m-- > 0;) {
      const size_t j = order[m];
      if (!boxes[j].contains(boxes[i]) || !point_in_polygon(probe, contours[j].points)) continue;
      contours[i].parent = int(j);
      depth[i] = depth[j] + 1;
      break;
    }
    Contour& c = contours[i];
    c.hole = depth[i] % 2 == 1;
    if ((signed_areas[i] > 0.0) == c.hole) std::reverse(c.points.begin(), c.points.end());
  }
}

}  // namespace rosmill::core::slice_detail
