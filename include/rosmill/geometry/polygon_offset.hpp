// Polygon offsetting and union of plane regions given as closed contours: Clipper's (polyclipping 6.4.2) with
// round joins, on integers of 1 nm. Contour toolpaths offset slices by the cutter's radius; roughing from a stock
// mesh grows the stock's sections by it.
#pragma once
#include <vector>

#include "rosmill/geometry/contour.hpp"

namespace rosmill::core {

// A closed cutter-location loop in XY; `around_material` is true for a loop around material (counter-clockwise
// before the cutting direction is applied) and false for one inside a hole or pocket.
struct OffsetLoop {
  std::vector<Vec2> points;
  bool around_material = true;
};

// The loops at `distance` from the region bounded by the closed contours of `region` (outer counter-clockwise,
// holes clockwise; open chains are ignored: they bound no region). Loops come counter-clockwise around material
// and clockwise in holes.
std::vector<OffsetLoop> offset_region(const std::vector<Contour>& region, double distance, double arc_tolerance);

// The union of two regions given as closed contours (outer counter-clockwise, holes clockwise), as contours of the
// same kind. Used to carry the part above a layer down to it: a flat end mill's body must clear all of it.
std::vector<Contour> union_regions(const std::vector<Contour>& a, const std::vector<Contour>& b);

}  // namespace rosmill::core
