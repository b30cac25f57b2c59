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

ToolpathStats toolpath_stats(const Toolpath& tp) {
  ToolpathStats s;
  Vec3 at = tp.start;
  for (const auto& p : tp.passes)
    for (const auto& m : p.moves) {
      const double len = (m.to - at).norm();
      ++s.moves;
      (m.type == MoveType::Rapid ? s.rapid_length : s.cutting_length) += len;
      at = m.to;
    }
  return s;
}

}  // namespace rosmill::core
