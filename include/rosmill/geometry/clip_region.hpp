// Plane regions as Clipper paths (polyclipping 6.4.2) on integers of 1 nm, and the operations planning does on
// them: offsets with round joins, booleans with the non-zero rule, areas. Outer boundaries run counter-clockwise
// and holes clockwise, as Clipper returns them.
#pragma once
#include <polyclipping/clipper.hpp>

#include <cmath>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::clip {

namespace cl = ClipperLib;
using Path = cl::Path;
using Paths = cl::Paths;

// 1 unit = 1 nm keeps rounding far below any machining tolerance and parts up to kilometres inside the 62-bit
// range Clipper computes in.
constexpr double kScale = 1e6;

inline cl::IntPoint to_point(const Vec2& v) {
  return cl::IntPoint(cl::cInt(std::llround(v.x() * kScale)), cl::cInt(std::llround(v.y() * kScale)));
}
inline Vec2 from_point(const cl::IntPoint& p) { return Vec2(double(p.X) / kScale, double(p.Y) / kScale); }
Path to_path(const std::vector<Vec2>& points);
std::vector<Vec2> from_path(const Path& path);

// The region grown by `distance` mm (shrunk when negative), round joins whose chords stay within
// `arc_tolerance` mm of the true arcs.
Paths offset(const Paths& region, double distance, double arc_tolerance);
// The area within `distance` mm of open polylines (a single point gives a disc), round ends and joins.
Paths sweep(const std::vector<std::vector<Vec2>>& polylines, double distance, double arc_tolerance);
// Morphological opening by r (shrunk by r, grown back): convex corners rounded to at least r, parts narrower
// than 2r dropped; the result lies inside the region.
Paths open(const Paths& region, double r, double arc_tolerance);
// Every loop with the fewest vertices that stay within `tolerance` mm of it (Ramer-Douglas-Peucker): the
// boundary moves by at most that much, either way.
Paths simplify(const Paths& region, double tolerance);
Paths unite(const Paths& a, const Paths& b);
Paths intersect(const Paths& a, const Paths& b);
Paths subtract(const Paths& a, const Paths& b);
// Even-odd fill of closed loops that may nest (island in a pocket in a part), as a non-zero region.
Paths even_odd(const Paths& loops);
double area(const Paths& region);  // mm^2: outer loops count positive, holes negative
Paths rectangle(const Vec2& lo, const Vec2& hi);
// Inside (or on the boundary of) the region, by the non-zero rule over its loops.
bool contains(const Paths& region, const Vec2& p);

}  // namespace rosmill::core::clip
