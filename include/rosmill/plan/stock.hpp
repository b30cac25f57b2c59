// Roughing stock given as a closed mesh (a casting, or the part as a previous stage left it) instead of the box.
// Each level removes the slab between it and the level above; the cutter there meets material only within its
// radius of the slab's outline, taken as the union of the stock's sections (slice/slicer) at the slab's bottom
// and every 1 mm up to its top, grown by the radius (Clipper). Cuts are kept to that grown outline, so roughing
// touches only material the stock has. A stock whose outline bulges out between two of those sections by more
// than the arc tolerance is under-covered by the bulge (a sphere's equator between two 1 mm sections is not).
#pragma once
#include <utility>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/polygon_offset.hpp"

namespace rosmill::core {

// Throws Error("stock", ...) when the stock is empty or not closed, or (when `part` is given) when a vertex of
// the part lies outside it (checked on at most a few thousand vertices, spread over the part).
void check_stock_mesh(const Mesh& stock, const Mesh* part);

// True when p is inside the closed mesh (parity of a vertical ray, up or down: a point on the stock's top or
// bottom face counts as inside).
bool inside_closed_mesh(const Mesh& mesh, const Vec3& p);

// The grown outlines of the slabs between consecutive levels (levels descending, the first slab from `top`).
class StockReach {
 public:
  StockReach(const Mesh& stock, const std::vector<double>& levels, double top, double radius,
             double arc_tolerance);
  // The intervals of s in [0, len] where origin + s dir (dir a unit vector) is within the radius of the slab
  // of level `level`, ascending.
  std::vector<std::pair<double, double>> along(size_t level, const Vec2& origin, const Vec2& dir,
                                               double len) const;
  // The reach outline of a level (for tests and drawing).
  const std::vector<OffsetLoop>& loops(size_t level) const { return loops_.at(level); }

 private:
  std::vector<std::vector<OffsetLoop>> loops_;
};

// The pieces of `spans` inside `keep` (both ascending, disjoint).
std::vector<std::pair<double, double>> intersect_spans(const std::vector<std::pair<double, double>>& spans,
                                                       const std::vector<std::pair<double, double>>& keep);

}  // namespace rosmill::core
