#include "rosmill/toolpath/toolpath_stats.hpp"

#include <cmath>

namespace rosmill::core {

double move_seconds(double length, const Vec3& dir, double feed, const Vec3& max_acceleration) {
  if (!(length > 0) || !(feed > 0)) return 0.0;
  const double v = feed / 60.0;  // mm/s
  double a = INFINITY;
  for (int i = 0; i < 3; ++i)
    if (max_acceleration[i] > 0 && std::abs(dir[i]) > 1e-12) a = std::min(a, max_acceleration[i] / std::abs(dir[i]));
  if (!std::isfinite(a)) return length / v;
  if (length >= v * v / a) return length / v + v / a;  // accelerate over v^2 / 2a, cruise, brake over v^2 / 2a
  return 2.0 * std::sqrt(length / a);                    // a triangle: the feed is never reached
}

ToolpathStats toolpath_stats(const Toolpath& tp, double rapid_feed, const Vec3& max_acceleration) {
  ToolpathStats s;
  Vec3 at = tp.start;
  for (const auto& p : tp.passes)
    for (const auto& m : p.moves) {
      const double len = (m.to - at).norm();
      const Vec3 dir = len > 0 ? Vec3((m.to - at) / len) : Vec3::Zero();
      ++s.moves;
      if (m.type == MoveType::Rapid) {
        s.rapid_length += len;
        s.estimated_seconds += move_seconds(len, dir, rapid_feed, max_acceleration);
      } else {
        s.cutting_length += len;
        s.estimated_seconds += move_seconds(len, dir, m.feed, max_acceleration);
      }
      at = m.to;
    }
  return s;
}

}  // namespace rosmill::core
