#include "rosmill/geometry/outline_from_above.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/geometry/polygon_offset.hpp"

namespace rosmill::core {
namespace {

constexpr double kSliverArea = 1e-6;  // mm²: a square micrometre

}  // namespace

std::vector<Contour> outline_from_above(const Mesh& mesh) {
  std::vector<Contour> shadows;
  shadows.reserve(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const Vec2 a = mesh.corner(f, 0).head<2>(), b = mesh.corner(f, 1).head<2>(), c = mesh.corner(f, 2).head<2>();
    const double twice_area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (twice_area == 0 || !std::isfinite(twice_area)) continue;  // seen edge-on: no area from above
    Contour shadow;
    // Counter-clockwise, so that with non-zero winding every shadow adds to the union and none cuts a hole.
    shadow.points = twice_area > 0 ? std::vector<Vec2>{a, b, c} : std::vector<Vec2>{a, c, b};
    shadows.push_back(std::move(shadow));
  }
  std::vector<Contour> outline = union_regions(shadows, {});
  // Triangles that share an edge meet on Clipper's nanometre grid with rounding: the union can keep slivers of
  // a few square nanometres between them, which are no part of the outline.
  outline.erase(std::remove_if(outline.begin(), outline.end(), [](const Contour& c) { return c.area < kSliverArea; }),
                outline.end());
  return outline;
}

}  // namespace rosmill::core
