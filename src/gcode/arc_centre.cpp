#include "rosmill/gcode/arc_centre.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::core::gcode {
namespace {

Vec2 centre_by_radius(const ArcWords& w, const Place& where) {
  const double r = w.radius * w.unit;
  const Vec2 chord = w.end - w.start;
  const double len = chord.norm();
  if (len == 0.0) throw Error(where.str(), "a full circle cannot be given with R");
  if (len > 2 * std::abs(r) + 1e-6) throw Error(where.str(), "arc radius R is smaller than half the chord");
  const double h = std::sqrt(std::max(0.0, r * r - 0.25 * len * len));
  const Vec2 right(chord.y() / len, -chord.x() / len);
  // G2 with R > 0 (an arc up to half a turn) has its centre right of the chord; R < 0 or G3 flip the side.
  const double side = (w.clockwise ? 1.0 : -1.0) * (r > 0 ? 1.0 : -1.0);
  return 0.5 * (w.start + w.end) + side * h * right;
}

Vec2 centre_by_offsets(const ArcWords& w, const Place& where) {
  if (!w.has_offset[0] && !w.has_offset[1]) throw Error(where.str(), "arc without I/J/K or R");
  const Vec2 ij = w.offset * w.unit;
  const Vec2 c = w.absolute_centre ? ij : Vec2(w.start + ij);
  const double r0 = (w.start - c).norm(), r1 = (w.end - c).norm();
  if (r0 == 0.0) throw Error(where.str(), "arc of zero radius");
  if (std::abs(r0 - r1) > 0.01 + 1e-3 * r0)
    throw Error(where.str(), "radius to the end of the arc differs from the radius to its start by " +
                                 std::to_string(std::abs(r0 - r1)) + " mm");
  return c;
}

}  // namespace

Vec2 arc_centre(const ArcWords& w, const Place& where) {
  if (w.has_radius) {
    if (w.has_offset[0] || w.has_offset[1]) throw Error(where.str(), "arc with both R and I/J/K");
    return centre_by_radius(w, where);
  }
  return centre_by_offsets(w, where);
}

}  // namespace rosmill::core::gcode
