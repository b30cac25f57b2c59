#include "rosmill/geometry/clip_region.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace rosmill::core::clip {

Path to_path(const std::vector<Vec2>& points) {
  Path p;
  p.reserve(points.size());
  for (const Vec2& v : points) p.push_back(to_point(v));
  return p;
}

std::vector<Vec2> from_path(const Path& path) {
  std::vector<Vec2> pts;
  pts.reserve(path.size());
  for (const cl::IntPoint& q : path) pts.push_back(from_point(q));
  return pts;
}

Paths offset(const Paths& region, double distance, double arc_tolerance) {
  // Clipper rounds the number of chords of a join to the nearest integer, which can make a chord up to 1.5 times
  // the angle its tolerance asks for and its gap 2.25 times larger: ask for 1/2.5 of the tolerance.
  cl::ClipperOffset o(2.0, std::max(arc_tolerance / 2.5, 1e-6) * kScale);
  o.AddPaths(region, cl::jtRound, cl::etClosedPolygon);
  Paths out;
  o.Execute(out, distance * kScale);
  return out;
}

Paths sweep(const std::vector<std::vector<Vec2>>& polylines, double distance, double arc_tolerance) {
  cl::ClipperOffset o(2.0, std::max(arc_tolerance / 2.5, 1e-6) * kScale);
  for (const auto& line : polylines)
    if (!line.empty()) o.AddPath(to_path(line), cl::jtRound, cl::etOpenRound);
  Paths out;
  o.Execute(out, distance * kScale);
  return out;
}

Paths open(const Paths& region, double r, double arc_tolerance) {
  if (!(r > 0)) return region;
  // Grown back a hair less than shrunk: the round trip's chords never reach out of the region.
  return offset(offset(region, -r, arc_tolerance), r - arc_tolerance, arc_tolerance);
}

namespace {

double distance_to_chord(const cl::IntPoint& p, const cl::IntPoint& a, const cl::IntPoint& b) {
  const Vec2 d = from_point(b) - from_point(a), v = from_point(p) - from_point(a);
  const double len2 = d.squaredNorm();
  if (len2 == 0) return v.norm();
  const double t = std::clamp(v.dot(d) / len2, 0.0, 1.0);
  return (v - t * d).norm();
}

// Marks the vertices of path[first..last] (inclusive, indices modulo n) that the simplified chain keeps.
void keep_vertices(const Path& path, size_t first, size_t last, double tolerance, std::vector<uint8_t>& keep) {
  const size_t n = path.size();
  std::vector<std::pair<size_t, size_t>> stack = {{first, last}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    double worst = 0;
    size_t at = a;
    for (size_t k = a + 1; k < b; ++k) {
      const double d = distance_to_chord(path[k % n], path[a % n], path[b % n]);
      if (d > worst) worst = d, at = k;
    }
    if (worst <= tolerance) continue;
    keep[at % n] = 1;
    stack.push_back({a, at});
    stack.push_back({at, b});
  }
}

Paths boolean(cl::ClipType type, const Paths& a, const Paths& b, cl::PolyFillType fill = cl::pftNonZero) {
  cl::Clipper c;
  c.AddPaths(a, cl::ptSubject, true);
  c.AddPaths(b, cl::ptClip, true);
  Paths out;
  c.Execute(type, out, fill, cl::pftNonZero);
  return out;
}

}  // namespace

Paths simplify(const Paths& region, double tolerance) {
  Paths out;
  for (const Path& path : region) {
    const size_t n = path.size();
    if (n < 4) {
      out.push_back(path);
      continue;
    }
    // A closed loop splits at its first vertex and the vertex farthest from it.
    size_t far = 0;
    double best = -1;
    for (size_t k = 1; k < n; ++k) {
      const double d = (from_point(path[k]) - from_point(path[0])).norm();
      if (d > best) best = d, far = k;
    }
    std::vector<uint8_t> keep(n, 0);
    keep[0] = keep[far] = 1;
    keep_vertices(path, 0, far, tolerance, keep);
    keep_vertices(path, far, n, tolerance, keep);
    Path kept;
    for (size_t k = 0; k < n; ++k)
      if (keep[k]) kept.push_back(path[k]);
    if (kept.size() >= 3) out.push_back(std::move(kept));
  }
  return out;
}

Paths unite(const Paths& a, const Paths& b) { return boolean(cl::ctUnion, a, b); }
Paths intersect(const Paths& a, const Paths& b) { return boolean(cl::ctIntersection, a, b); }
Paths subtract(const Paths& a, const Paths& b) { return boolean(cl::ctDifference, a, b); }
Paths even_odd(const Paths& loops) { return boolean(cl::ctUnion, loops, {}, cl::pftEvenOdd); }

double area(const Paths& region) {
  double a = 0;
  for (const Path& p : region) a += cl::Area(p);
  return a / (kScale * kScale);
}

Paths rectangle(const Vec2& lo, const Vec2& hi) {
  return {to_path({lo, Vec2(hi.x(), lo.y()), hi, Vec2(lo.x(), hi.y())})};
}

bool contains(const Paths& region, const Vec2& p) {
  const cl::IntPoint q = to_point(p);
  int winding = 0;
  for (const Path& path : region) {
    const int in = cl::PointInPolygon(q, path);
    if (in == -1) return true;
    if (in == 1) winding += cl::Orientation(path) ? 1 : -1;
  }
  return winding != 0;
}

}  // namespace rosmill::core::clip
