#include "rosmill/geometry/polygon_offset.hpp"

#include "rosmill/geometry/clip_region.hpp"

#include <algorithm>
#include <cmath>

namespace rosmill::core {
namespace {

namespace cl = ClipperLib;
using clip::kScale;

cl::Paths to_paths(const std::vector<Contour>& region) {
  cl::Paths out;
  for (const Contour& c : region)
    if (c.closed && c.points.size() >= 3) out.push_back(clip::to_path(c.points));
  return out;
}

}  // namespace

std::vector<Contour> union_regions(const std::vector<Contour>& a, const std::vector<Contour>& b) {
  // Non-zero winding: outer loops count +1 and holes -1, so a hole of one region covered by the other is filled.
  const cl::Paths merged = clip::unite(to_paths(a), to_paths(b));
  std::vector<Contour> out;
  for (const cl::Path& p : merged) {
    Contour c;
    c.points = clip::from_path(p);
    c.hole = !cl::Orientation(p);
    c.area = std::abs(cl::Area(p)) / (kScale * kScale);
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<OffsetLoop> offset_region(const std::vector<Contour>& region, double distance, double arc_tolerance) {
  const cl::Paths loops = clip::offset(to_paths(region), distance, arc_tolerance);
  std::vector<OffsetLoop> out;
  for (const cl::Path& p : loops) out.push_back({clip::from_path(p), cl::Orientation(p)});
  return out;
}

}  // namespace rosmill::core
