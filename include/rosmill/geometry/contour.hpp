// A plane outline: a chain of points in XY, closed or open, oriented by what it bounds. Slicing makes them
// (slice/slicer.hpp); polygon offsetting (polygon_offset.hpp) and regions take them.
#pragma once
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

// One chain of the section. Closed contours are oriented counter-clockwise seen from +Z when they bound material
// (outer) and clockwise when they bound a hole; `parent` is the index (in the layer) of the nearest contour that
// encloses it, -1 at top level. Open chains exist only where the mesh is open; they keep the direction of the
// faces they cross and have no area, hole flag or parent.
struct Contour {
  std::vector<Vec2> points;  // the closing segment from back() to front() is implied for a closed contour
  bool closed = true;
  bool hole = false;
  double area = 0.0;  // mm², positive
  int parent = -1;
};

}  // namespace rosmill::core
