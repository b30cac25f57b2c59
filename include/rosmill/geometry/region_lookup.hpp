// Whether points lie in a plane region, in constant time for the many queries a planner makes against one region
// (a pass keeping its cutter out of the part), where clip::contains walks every vertex of every loop.
//
// A grid over the region's box: each cell is wholly inside, wholly outside, or crossed by the boundary. A crossed
// cell keeps the boundary's edges through it and whether its centre lies inside; a point there is inside when the
// segment from the centre to it crosses an even number of those edges and the centre is inside, or an odd number
// and it is not (the crossing-number test of point location, on the cell's few edges). A point on an edge counts
// as inside, as clip::contains counts the boundary. Loops must not overlap (Clipper's booleans return them so).
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/geometry/clip_region.hpp"

namespace rosmill::core {

class RegionLookup {
 public:
  RegionLookup() = default;
  // `cell`: the grid's cell edge (mm); cells that hold a few edges each keep the queries fast.
  RegionLookup(const clip::Paths& region, double cell);
  bool contains(const Vec2& p) const;

 private:
  // kExact: a crossed cell whose centre lies on the boundary, asked of the region itself.
  enum State : uint8_t { kOut = 0, kIn = 1, kCrossed = 2, kExact = 3 };
  struct Edge {
    Vec2 a, b;
  };
  void classify_open_cells(const clip::Paths& region);
  Vec2 centre_of(size_t c) const;
  double x0_ = 0, y0_ = 0, cell_ = 1;
  long nx_ = 0, ny_ = 0;
  std::vector<uint8_t> state_;
  std::vector<uint8_t> centre_in_;  // crossed cells: whether the centre lies inside
  std::vector<uint32_t> first_;     // crossed cells: their edges are edge_ids_[first_[c] .. first_[c + 1])
  std::vector<uint32_t> edge_ids_;
  std::vector<Edge> edges_;
  clip::Paths region_;  // only when some cell is kExact
};

}  // namespace rosmill::core
