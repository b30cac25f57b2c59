#include "rosmill/geometry/polygon_offset.hpp"

#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <cmath>

namespace rosmill::core {
namespace {

namespace cl = ClipperLib;

// Clipper works on integers: 1 unit = 1 nm keeps rounding far below any machining tolerance and parts up to
// kilometres inside its 62-bit range.
constexpr double kScale = 1e6;

cl::Path to_path(const std::vector<Vec2>& pts) {
  cl::Path p;
  p.reserve(pts.size());
  for (const Vec2& v : pts)
    p.emplace_back(cl::cInt(std::llround(v.x() * kScale)), cl::cInt(std::llround(v.y() * kScale)));
  return p;
}

std::vector<Vec2> from_path(const cl::Path& p) {
  std::vector<Vec2> pts;
  pts.reserve(p.size());
  for (const cl::IntPoint& q : p) pts.emplace_back(double(q.X) / kScale, double(q.Y) / kScale);
  return pts;
}

cl::Paths to_paths(const std::vector<Contour>& region) {
  cl::Paths out;
  for (const Contour& c : region)
    if (c.closed && c.points.size() >= 3) out.push_back(to_path(c.points));
  return out;
}

}  // namespace

std::vector<Contour> union_regions(const std::vector<Contour>& a, const std::vector<Contour>& b) {
  cl::Clipper clipper;
  clipper.AddPaths(to_paths(a), cl::ptSubject, true);
  clipper.AddPaths(to_paths(b), cl::ptSubject, true);
  cl::Paths merged;
  // Non-zero winding: outer loops count +1 and holes -1, so a hole of one region covered by the other is filled.
  clipper.Execute(cl::ctUnion, merged, cl::pftNonZero, cl::pftNonZero);
  std::vector<Contour> out;
  for (const cl::Path& p : merged) {
    Contour c;
    c.points = from_path(p);
    c.hole = !cl::Orientation(p);
    c.area = std::abs(cl::Area(p)) / (kScale * kScale);
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<OffsetLoop> offset_region(const std::vector<Contour>& region, double distance, double arc_tolerance) {
  // Clipper rounds the number of chords of a join to the nearest integer, which can make a chord up to 1.5 times
  // the angle its tolerance asks for and its gap 2.25 times larger: ask for 1/2.5 of the tolerance.
  cl::ClipperOffset offset(2.0, std::max(arc_tolerance / 2.5, 1e-6) * kScale);
  offset.AddPaths(to_paths(region), cl::jtRound, cl::etClosedPolygon);
  cl::Paths loops;
  offset.Execute(loops, distance * kScale);
  std::vector<OffsetLoop> out;
  for (const cl::Path& p : loops) out.push_back({from_path(p), cl::Orientation(p)});
  return out;
}

}  // namespace rosmill::core
