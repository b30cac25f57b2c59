#include "rosmill/plan/checked_surface.hpp"

#include <algorithm>

namespace rosmill::core {

Drop CheckedSurface::drop(const Cutter& cutter, double x, double y) const {
  const Drop d = drive_.drop(cutter, x, y), c = check_.drop(cutter, x, y);
  if (!c.touched) return d;
  if (!d.touched || c.z > d.z) return c;
  return d;
}

bool CheckedSurface::held_above(const Cutter& cutter, double x, double y, double z) const {
  return drive_.held_above(cutter, x, y, z) || check_.held_above(cutter, x, y, z);
}

SweepHit CheckedSurface::sweep(const Cutter& cutter, const Vec3& a, const Vec3& b, double floor) const {
  const SweepHit d = drive_.sweep(cutter, a, b, floor), c = check_.sweep(cutter, a, b, floor);
  return c.depth > d.depth ? c : d;
}

// The check surface (a fixture) holds the cutter far beside the part too, but a waterline follows the part: its
// contours of the check surface are cut off where its grid ends, and left open there (waterline.hpp).
double CheckedSurface::held_reach() const { return drive_.held_reach(); }

}  // namespace rosmill::core
