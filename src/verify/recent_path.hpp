// The last few millimetres of the cutter's path, held exactly rather than in the stock's cells: how low the cutter
// passed strictly within its radius of a point. The engagement measurement reads the stock's cells for what the
// older path left and asks this for the recent path, whose cut edge runs close to the cutter's circle at its sides
// (at a distance of h cos(alpha) + O(h^2) a path length h back): there a cell's rounding would read a whole range of
// the circle as cut (see engagement.cpp).
#pragma once
#include <deque>

#include "rosmill/toolpath/canon_move.hpp"

namespace rosmill::core::verify {

// The lowest tip height of `move`, between its start and the fraction `until` of it, at the positions strictly
// within `reach` of (x, y) in XY; +infinity when none is. Lines (a plunge too) and XY arcs (z linear along them).
double lowest_pass_within(const CanonMove& move, double until, double x, double y, double reach);

// A disc in XY that holds every position of a move: a point farther than `reach` from the disc is farther than that
// from the move, so a reader of many points can pass over the move for all of them at once.
struct Footprint {
  Vec2 centre = Vec2::Zero();
  double radius = 0;
};
Footprint footprint(const CanonMove& move);

class RecentPath {
 public:
  struct Piece {
    CanonMove move;
    size_t index;  // in its program
    double end;    // the path's XY length at its end
    Footprint disc;
  };
  void add(const CanonMove& move, size_t index, double end) {
    pieces_.push_back({move, index, end, footprint(move)});
  }
  bool empty() const { return pieces_.empty(); }
  const Piece& oldest() const { return pieces_.front(); }
  void drop_oldest() { pieces_.pop_front(); }
  auto begin() const { return pieces_.begin(); }
  auto end() const { return pieces_.end(); }

 private:
  std::deque<Piece> pieces_;
};

}  // namespace rosmill::core::verify
