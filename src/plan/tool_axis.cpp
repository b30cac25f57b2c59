#include "rosmill/plan/tool_axis.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace rosmill::core {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The unit vector at `angle` (radians) from unit `a` towards unit `b`, in their plane; `a` when they are parallel.
Vec3 slerp_by_angle(const Vec3& a, const Vec3& b, double angle) {
  Vec3 side = b - a.dot(b) * a;
  const double len = side.norm();
  if (len < 1e-15) return a;
  side /= len;
  return (std::cos(angle) * a + std::sin(angle) * side).normalized();
}

}  // namespace

double angle_between_deg(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)) / kDeg; }

Vec3 lead_tilt_axis(const Vec3& n, const Vec3& travel, double lead_deg, double tilt_deg) {
  Vec3 f = travel - travel.dot(n) * n;
  const double len = f.norm();
  if (len < 1e-12) return n;
  f /= len;
  const Vec3 right = f.cross(n);  // to the right of travel, seen from above the surface
  const double lead = lead_deg * kDeg, tilt = tilt_deg * kDeg;
  return (std::cos(lead) * std::cos(tilt) * n + std::sin(lead) * f + std::cos(lead) * std::sin(tilt) * right)
      .normalized();
}

Vec3 within_cone(const Vec3& axis, double cone_deg) {
  const Vec3 z = Vec3::UnitZ();
  const double off = angle_between_deg(z, axis);
  if (off <= cone_deg) return axis;
  // Straight down has no plane with +Z: any side will do, +X is taken.
  const Vec3 towards = axis.head<2>().norm() < 1e-12 ? Vec3(Vec3::UnitX()) : Vec3(axis.x(), axis.y(), 0).normalized();
  return (std::cos(cone_deg * kDeg) * z + std::sin(cone_deg * kDeg) * towards).normalized();
}

Vec3 turn_towards(const Vec3& from, const Vec3& to, double max_deg) {
  const double off = angle_between_deg(from, to);
  if (off <= max_deg) return to;
  return slerp_by_angle(from, to, max_deg * kDeg);
}

}  // namespace rosmill::core
