// Dubins paths: the shortest curves from one pose (point and heading) to another whose curvature stays under
// 1 / rho, made of at most three pieces, each an arc of radius rho (L left, R right) or a straight line (S)
// (Dubins, "On curves of minimal length with a constraint on average curvature, and with prescribed initial and
// terminal positions and tangents", 1957). The six candidate words and their closed forms follow Shkel and
// Lumelsky, "Classification of the Dubins set", 2001. Adaptive clearing links its passes by them, so that the
// cutter turns no sharper than its turn radius between one cut and the next.
#pragma once
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

struct DubinsPath {
  char word[3] = {'S', 'S', 'S'};  // each piece: 'L', 'R' or 'S'
  double piece[3] = {0, 0, 0};     // lengths in units of rho (an arc's: the angle it turns, radians)
  double rho = 1;
  double length() const { return rho * (piece[0] + piece[1] + piece[2]); }
};

// Every word that joins the poses, shortest first (none when the poses coincide).
std::vector<DubinsPath> dubins_paths(const Vec2& from, const Vec2& from_heading, const Vec2& to,
                                     const Vec2& to_heading, double rho);

// Points along a path from `from` (heading `from_heading`, unit), every `step` at most, the last the path's end.
std::vector<Vec2> dubins_points(const DubinsPath& path, const Vec2& from, const Vec2& from_heading, double step);

}  // namespace rosmill::core
