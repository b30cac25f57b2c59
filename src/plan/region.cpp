#include "rosmill/plan/region.hpp"

#include "rosmill/error.hpp"

namespace rosmill::core {

bool inside_region(const Region& region, const Vec2& p) {
  bool inside = false;
  for (const std::vector<Vec2>& loop : region)
    for (size_t j = 0, k = loop.size() - 1; j < loop.size(); k = j++) {
      const Vec2& a = loop[j];
      const Vec2& b = loop[k];
      // Crossings of the ray from p towards +x (half-open in y, so a vertex on the ray counts once).
      if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
        inside = !inside;
    }
  return inside;
}

Region patch_region(const Mesh& mesh, const segment::Patch& patch) {
  Region region;
  for (const segment::BoundaryLoop& loop : patch.loops) {
    if (!loop.closed || loop.vertices.size() < 3) continue;
    std::vector<Vec2> xy;
    xy.reserve(loop.vertices.size());
    for (uint32_t v : loop.vertices) xy.push_back(mesh.vertices.at(v).head<2>());
    region.push_back(std::move(xy));
  }
  if (region.empty()) throw Error("patch " + std::to_string(patch.id), "has no closed boundary loop to machine inside");
  return region;
}

}  // namespace rosmill::core
