// The workpiece's material as planning sees it: the top of material per square cell of an XY grid in the plan's
// frame (minus infinity where a cell has none), optionally the top of the material an operation may remove (what
// stands above the design by more than the allowance) and the cells an operation keeps to (rest material, the faces
// its setup finishes). Planning knows no stock model; a job fills this from its in-process stock seen from the
// operation's setup, so that roughing cuts only where material is left to cut and links low over what stands
// (the fixture too), and a rest or setup-bound operation keeps to its cells. A height per cell (not polygons like Region) because that is what the stock is and what every query
// here asks: "the highest material under this cutter" is a maximum over the cells the cutter's disc covers.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "rosmill/geometry/segment_distance.hpp"
#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

struct MaterialTop {
  double x0 = 0.0, y0 = 0.0;  // lower-left corner of cell (0, 0), mm
  double cell = 1.0;          // cell edge, mm
  int nx = 0, ny = 0;
  std::vector<float> top;     // nx * ny, row by row (j * nx + i): top of material, -infinity where none
  std::vector<float> cut;     // empty (all of `top`), or nx * ny: the top of the material an operation may remove,
                              // -infinity where what stands is the design plus the allowance, or the fixture
  std::vector<float> fixture; // empty, or nx * ny: the top of the fixture holding the part (-infinity where none):
                              // links and the safe height clear it as they clear the material
  std::vector<uint8_t> keep;  // empty, or nx * ny: 1 where the operation's moves are kept (kept_moves.hpp): rest
                              // material above the design by more than the allowance and the rest threshold, or
                              // the faces the operation's setup finishes
  // Empty (a kept cell keeps every height), or nx * ny: the lowest and highest the kept surface stands in each kept
  // cell, so that a cut at another height over the same cell (a wall below a face that another setup finishes)
  // is not kept.
  std::vector<float> keep_low, keep_high;

  // Throws Error naming `where` when the sizes disagree or the cell is not a positive number.
  void check(const std::string& where) const;
  bool keeps() const { return !keep.empty(); }
  // Grows the grid by `cells` on every side: no material, no fixture and nothing kept there. A job pads the stock's
  // grid so that planning also sees the fixture beside the stock, where the cutter reaches when it clears the
  // stock's edges, and then fills `fixture` on the grown grid.
  void pad(int cells);
  double highest() const;  // of the material and the fixture over the whole grid; -infinity when empty
  Box3 extent() const;     // the squares of the cells with material, and their heights (empty without)
  // What stands in cell c: the material, or the fixture where it is higher.
  double standing(size_t c) const { return fixture.empty() ? top[c] : std::max(top[c], fixture[c]); }
  // The highest material (or fixture) a cutter of `radius` with its axis on the segment a-b may meet: over the cells whose
  // centre lies within radius + one cell of the segment (a cell's material may reach half a cell beyond its
  // centre, and its neighbour's another half). -infinity when none.
  double highest_along(const Vec2& a, const Vec2& b, double radius) const;
  double highest_under(const Vec2& p, double radius) const { return highest_along(p, p, radius); }
  // The same for every cell at once: a grid grown by the reach on every side whose cell holds the highest material
  // (or fixture) of the cells within `reach` of its centre, each cell's material reaching half a diagonal beyond its
  // own centre (the disc as rows, each row's running maximum in van Herk and Gil-Werman's two passes). What a body
  // much wider than the cutter (a holder) asks at every sample of a level.
  MaterialTop highest_within(double reach) const;
  // The top of the cell holding p; -infinity outside the grid.
  double top_at(const Vec2& p) const;
  // The same over the material an operation may remove (`cut`, else `top`).
  double highest_cut_under(const Vec2& p, double radius) const;
  // The lowest tip height at p at which a cutter (`radius`; lift(d): its bottom's height above the tip at distance d
  // from the axis) stands clear of the material at every cell centre under it: what the stock model, which samples
  // the same centres, finds the cutter touching as it comes down there. -infinity when there is no material.
  template <class Lift>
  double clear_height(const Vec2& p, double radius, const Lift& lift) const;
  // True when a kept cell's centre lies within `radius` of p and its kept heights meet [z - below, z + above] (a
  // cutter with its tip at z touches the surface from below its tip, by rounding, to its corner's top).
  bool keep_near(const Vec2& p, double radius, double z = NAN, double below = 0, double above = 0) const;
  // What a cutter with its tip at z along a-b has certainly cut: every cell whose whole square lies within the
  // disc swept by `radius` is lowered to at most z + lift(d), d the farthest its square gets from the axis (lift:
  // the cutter's bottom at that distance above its tip; 0 for a flat end mill).
  template <class Lift>
  void lower_along(const Vec2& a, const Vec2& b, double radius, double z, const Lift& lift);

 private:
  // Calls f(index, distance of the cell centre to the segment) for the cells whose centre is within `reach` and
  // that wanted(index) passes (asked first: it is cheaper than the distance).
  template <class Wanted, class F>
  void cells_near(const Vec2& a, const Vec2& b, double reach, const Wanted& wanted, const F& f) const;
  template <class F>
  void cells_near(const Vec2& a, const Vec2& b, double reach, const F& f) const {
    cells_near(a, b, reach, [](size_t) { return true; }, f);
  }
};

template <class Wanted, class F>
void MaterialTop::cells_near(const Vec2& a, const Vec2& b, double reach, const Wanted& wanted, const F& f) const {
  if (nx <= 0 || ny <= 0) return;
  const auto clamp_index = [](double u, int n) { return u < 0 ? 0 : u > n - 1 ? n - 1 : static_cast<int>(u); };
  const int i0 = clamp_index(std::floor((std::min(a.x(), b.x()) - reach - x0) / cell), nx);
  const int i1 = clamp_index(std::ceil((std::max(a.x(), b.x()) + reach - x0) / cell), nx);
  const int j0 = clamp_index(std::floor((std::min(a.y(), b.y()) - reach - y0) / cell), ny);
  const int j1 = clamp_index(std::ceil((std::max(a.y(), b.y()) + reach - y0) / cell), ny);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const size_t c = static_cast<size_t>(j) * nx + i;
      if (!wanted(c)) continue;
      const double d = segment_distance(Vec2(x0 + (i + 0.5) * cell, y0 + (j + 0.5) * cell), a, b);
      if (d <= reach) f(c, d);
    }
}

template <class Lift>
double MaterialTop::clear_height(const Vec2& p, double radius, const Lift& lift) const {
  double h = -INFINITY;
  cells_near(p, p, radius, [&](size_t c, double d) { h = std::max(h, standing(c) - lift(d)); });
  return h;
}

template <class Lift>
void MaterialTop::lower_along(const Vec2& a, const Vec2& b, double radius, double z, const Lift& lift) {
  const double corner = 0.5 * cell * std::sqrt(2.0);  // centre to corner of a cell
  // A cell at or below z stays: the cutter's bottom is nowhere below its tip (lift >= 0). Along a level's
  // overlapping moves most cells under a move were lowered by the last, so this skips most distances.
  const auto above = [&](size_t c) { return top[c] > z; };
  cells_near(a, b, radius - corner, above, [&](size_t c, double d) {
    top[c] = std::min(top[c], static_cast<float>(z + lift(d + corner)));
  });
}

}  // namespace rosmill::core
