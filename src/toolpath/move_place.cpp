#include "rosmill/toolpath/move_place.hpp"

#include <cstdio>

namespace rosmill::core {
namespace {

std::string point_text(const Vec3& p) {
  char s[96];
  std::snprintf(s, sizeof s, "(%.3f, %.3f, %.3f)", p.x() + 0.0, p.y() + 0.0, p.z() + 0.0);
  return s;
}

const char* kind_of(MoveType t) {
  switch (t) {
    case MoveType::Rapid: return "a rapid";
    case MoveType::Feed: return "a feed";
    case MoveType::Plunge: return "a plunge";
  }
  return "a move";
}

}  // namespace

std::string move_place(const Job& job, uint32_t number) {
  uint32_t n = 0;
  for (size_t t = 0; t < job.size(); ++t) {
    Vec3 at = job[t].start;
    for (const ToolpathPass& pass : job[t].passes)
      for (const Move& m : pass.moves) {
        if (++n == number)
          return "move " + std::to_string(number) + ": toolpath " + std::to_string(t + 1) + " (" + job[t].strategy +
                 "), pass '" + pass.name + "', " + kind_of(m.type) + " from " + point_text(at) + " to " +
                 point_text(m.to);
        at = m.to;
      }
  }
  return "move " + std::to_string(number);
}

}  // namespace rosmill::core
