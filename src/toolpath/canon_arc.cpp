#include "rosmill/toolpath/canon_arc.hpp"

#include <cmath>

namespace rosmill::core {

PlaneAxes plane_axes(Plane plane) {
  switch (plane) {
    case Plane::ZX: return {2, 0, 1};
    case Plane::YZ: return {1, 2, 0};
    default: return {0, 1, 2};
  }
}


double arc_sweep(const CanonMove& arc) {
  const Vec2 a = arc.from.head<2>() - arc.centre, b = arc.to.head<2>() - arc.centre;
  double ccw = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));  // (-π, π]
  if (ccw <= 0) ccw += 2 * M_PI;                                      // (0, 2π]: equal ends make a full turn
  if (arc.shape == MoveShape::ArcCCW) return ccw;
  return ccw - 2 * M_PI == 0.0 ? -2 * M_PI : ccw - 2 * M_PI;          // [-2π, 0)
}

double move_length(const CanonMove& move) {
  if (move.shape == MoveShape::Line) return (move.to - move.from).norm();
  const double xy = (move.from.head<2>() - move.centre).norm() * std::abs(arc_sweep(move));
  return std::hypot(xy, move.to.z() - move.from.z());
}

Vec3 move_point(const CanonMove& move, double s) {
  if (move.shape == MoveShape::Line) return move.from + s * (move.to - move.from);
  const Vec2 a = move.from.head<2>() - move.centre;
  const double angle = s * arc_sweep(move), c = std::cos(angle), sn = std::sin(angle);
  const Vec2 p = move.centre + Vec2(c * a.x() - sn * a.y(), sn * a.x() + c * a.y());
  return Vec3(p.x(), p.y(), move.from.z() + s * (move.to.z() - move.from.z()));
}

void move_xy_bounds(const CanonMove& move, Vec2& min, Vec2& max) {
  min = move.from.head<2>().cwiseMin(move.to.head<2>());
  max = move.from.head<2>().cwiseMax(move.to.head<2>());
  if (move.shape == MoveShape::Line) return;
  const Vec2 a = move.from.head<2>() - move.centre;
  const double rho = a.norm(), start = std::atan2(a.y(), a.x()), sweep = arc_sweep(move);
  // The axis-extreme points (angles k·π/2) that the sweep passes.
  for (int k = -8; k <= 8; ++k) {
    const double angle = k * 0.5 * M_PI;
    const double rel = sweep > 0 ? angle - start : start - angle;
    if (rel >= 0 && rel <= std::abs(sweep)) {
      const Vec2 p = move.centre + rho * Vec2(std::cos(angle), std::sin(angle));
      min = min.cwiseMin(p);
      max = max.cwiseMax(p);
    }
  }
}

}  // namespace rosmill::core
