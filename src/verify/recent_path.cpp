#include "recent_path.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/toolpath/canon_arc.hpp"

namespace rosmill::core::verify {
namespace {

constexpr double kInf = INFINITY;

double z_at(const CanonMove& m, double t) { return m.from.z() + t * (m.to.z() - m.from.z()); }

// Parameters t in [0, until] of a line whose XY point lies within `reach` of (x, y): the roots of
// |a + t d - p|^2 = reach^2; the lower end of the line's z between them.
double line_lowest(const CanonMove& m, double until, double x, double y, double reach) {
  const Vec2 a = m.from.head<2>(), d = (m.to - m.from).head<2>(), e = a - Vec2(x, y);
  const double dd = d.squaredNorm(), c = e.squaredNorm() - reach * reach;
  if (dd < 1e-18) return c < 0 ? std::min(m.from.z(), z_at(m, until)) : kInf;
  const double b = e.dot(d), disc = b * b - dd * c;
  if (disc <= 0) return kInf;
  const double root = std::sqrt(disc);
  const double t0 = std::max(0.0, (-b - root) / dd), t1 = std::min(until, (-b + root) / dd);
  return t0 < t1 ? std::min(z_at(m, t0), z_at(m, t1)) : kInf;
}

// The same for an XY arc: the positions within reach are those within an angle w of the point's direction from the
// centre (law of cosines), taken along the arc's sweep from its start, one turn back or on.
double arc_lowest(const CanonMove& m, double until, double x, double y, double reach) {
  const Vec2 a = m.from.head<2>() - m.centre, e = Vec2(x, y) - m.centre;
  const double rho = a.norm(), dist = e.norm(), sweep = arc_sweep(m), total = std::abs(sweep);
  const double travelled = total * until;
  if (dist < 1e-12 || rho < 1e-12) return rho < reach || dist < reach ? std::min(m.from.z(), z_at(m, until)) : kInf;
  const double cos_w = (rho * rho + dist * dist - reach * reach) / (2 * rho * dist);
  if (cos_w >= 1) return kInf;
  if (cos_w <= -1) return std::min(m.from.z(), z_at(m, until));
  const double w = std::acos(cos_w);
  const double sign = sweep < 0 ? -1.0 : 1.0;
  double offset = sign * (std::atan2(e.y(), e.x()) - std::atan2(a.y(), a.x()));
  offset = std::fmod(offset, 2 * M_PI);
  if (offset < 0) offset += 2 * M_PI;
  double lowest = kInf;
  for (int k = -1; k <= 1; ++k) {
    const double lo = std::max(0.0, offset - w + 2 * M_PI * k), hi = std::min(travelled, offset + w + 2 * M_PI * k);
    if (lo < hi) lowest = std::min({lowest, z_at(m, lo / total), z_at(m, hi / total)});
  }
  return lowest;
}

}  // namespace

double lowest_pass_within(const CanonMove& move, double until, double x, double y, double reach) {
  return move.is_arc() ? arc_lowest(move, until, x, y, reach) : line_lowest(move, until, x, y, reach);
}

Footprint footprint(const CanonMove& move) {
  Vec2 lo, hi;
  move_xy_bounds(move, lo, hi);
  return {0.5 * (lo + hi), 0.5 * (hi - lo).norm()};
}

}  // namespace rosmill::core::verify
