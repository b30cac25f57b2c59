// The centre of a G2/G3 arc from its words, in the coordinates of its plane (first and second axis): by the
// offsets I J K from the start (or absolute, G90.1), or by the radius R (R < 0: the long way round).
#pragma once
#include "rosmill/gcode/block.hpp"
#include "rosmill/geometry/types.hpp"

namespace rosmill::core::gcode {

struct ArcWords {
  Vec2 start = Vec2::Zero(), end = Vec2::Zero();  // mm, in the plane
  bool clockwise = false;
  double unit = 1.0;                 // mm per program unit
  bool has_radius = false;
  double radius = 0.0;               // R, program units
  bool has_offset[2] = {false, false};
  Vec2 offset = Vec2::Zero();        // the plane's two offset words, program units
  bool absolute_centre = false;      // G90.1
};

// Throws Error at `where` on an arc RS274/NGC refuses: neither or both of R and the offsets, a full circle by R,
// R smaller than half the chord, a zero radius, or ends at radii that differ by more than 0.01 mm + 0.1 %.
Vec2 arc_centre(const ArcWords& words, const Place& where);

}  // namespace rosmill::core::gcode
