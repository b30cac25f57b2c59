#include "rosmill/toolpath/toolpath_stats.hpp"

namespace rosmill::core {

ToolpathStats toolpath_stats(const Toolpath& tp, double rapid_feed) {
  ToolpathStats s;
  Vec3 at = tp.start;
  for (const auto& p : tp.passes)
    for (const auto& m : p.moves) {
      const double len = (m.to - at).norm();
      ++s.moves;
      if (m.type == MoveType::Rapid) {
        s.rapid_length += len;
        s.estimated_seconds += 60.0 * len / rapid_feed;
      } else {
        s.cutting_length += len;
        if (m.feed > 0) s.estimated_seconds += 60.0 * len / m.feed;
      }
      at = m.to;
    }
  return s;
}

}  // namespace rosmill::core
