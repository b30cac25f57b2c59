// Orientation and nesting of a layer's closed contours: which contour lies inside which, outer
// counter-clockwise, holes clockwise.
#pragma once
#include <vector>

#include "rosmill/slice/slicer.hpp"

namespace rosmill::core::slice_detail {

// Sets area, hole and parent of every closed contour of `contours` and reverses those whose direction disagrees
// with their depth (even depth: outer, counter-clockwise; odd depth: hole, clockwise). Open chains are left as
// they are. The parent of a contour is the smallest closed contour containing one of its points (sections of a
// solid never cross, so one point decides).
void orient_and_nest(std::vector<Contour>& contours);

// Crossing-number test; a point exactly on the boundary may go either way.
bool point_in_polygon(const Vec2& p, const std::vector<Vec2>& polygon);

}  // namespace rosmill::core::slice_detail
