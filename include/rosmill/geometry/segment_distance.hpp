// The distance from a point to a segment in the plane: inline, for the loops over cells and edges that ask it
// for every cell.
#pragma once
#include <algorithm>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

inline double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

}  // namespace rosmill::core
