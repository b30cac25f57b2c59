// The moves a setup's programs swept, kept so that the removal envelope can be read exactly at any point, not only
// at the centres of its cells: the lowest cutter bottom over (x, y) is the least, over the moves whose footprint
// covers it, of the same closed forms the removal kernels use (sweep_kernels.hpp), read at that one point. A grid
// of bins over the setup's XY lists the moves whose footprint (the capsule of the cutter's radius around the path)
// meets each bin. InProcessStock keeps one per setup and answers its exact point queries through it.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/cutter/contact.hpp"
#include "rosmill/stock/height_field.hpp"
#include "rosmill/stock/program.hpp"

namespace rosmill::core::stock {

namespace sweep {
struct LineFrame;  // the removal kernels' frame of a line (src/stock/sweep_geometry.hpp)
}

// How near a cutter comes to a point for SweptMoves::comes_near by default (mm).
constexpr double kNearCut = 0.005;

class SweptMoves {
 public:
  // Bins over the setup's grid `g` (a bin is a few of its cells, about `bin_mm` wide); moves beyond the grid count
  // in its border bins (no material lies beyond it).
  SweptMoves();  // no moves
  // `near_mm`: how near a cutter must come to a point for comes_near.
  explicit SweptMoves(const GridSpec& g, double bin_mm = 2.0, double near_mm = kNearCut);
  ~SweptMoves();
  SweptMoves(const SweptMoves&);
  SweptMoves& operator=(const SweptMoves&);
  SweptMoves(SweptMoves&&) noexcept;
  SweptMoves& operator=(SweptMoves&&) noexcept;

  // Keeps every move of `program` (in the setup's frame): lines and level XY arcs as they are, helices as chords
  // within `arc_tolerance` (as the removal simulation sweeps them).
  void add(const MachineProgram& program, double arc_tolerance = 0.001);

  // The lowest cutter bottom any kept move passes over (x, y); +infinity where none does.
  double lowest_bottom(double x, double y) const;
  // True when some kept move's cutter reaches down to z or lower over (x, y): the point (x, y, z) is cut away.
  bool removes(double x, double y, double z) const;
  // True when some kept move's cutter, grown by the near distance on every side (offset_cutter), reaches the point:
  // the point lies within that distance of what was cut away.
  bool comes_near(double x, double y, double z) const;
  double near() const { return near_; }

  // The kept moves whose cutter, grown by the near distance, can reach a point within `radius` of c (into `ids`,
  // replaced): among them alone, removes_among and comes_near_among answer as removes and comes_near do for every
  // point of that ball. A move is passed over when even its lowest tip, lifted by its cutter's rise at the least
  // distance the ball's points can have from its axis path, stays above the ball.
  void gather(const Vec3& c, double radius, std::vector<uint32_t>& ids) const;
  bool removes_among(const std::vector<uint32_t>& ids, double x, double y, double z) const;
  bool comes_near_among(const std::vector<uint32_t>& ids, double x, double y, double z) const;

  size_t size() const { return pieces_.size(); }
  size_t bytes() const;

 private:
  struct Piece {
    Vec3 from, to;
    Vec2 centre;        // a level arc's
    MoveShape shape;    // Line, or a level XY arc
    uint16_t profile;   // into profiles_
    double lowest;      // the tip's lowest: the cutter's bottom over any point is no lower
  };
  double bottom(const Piece& p, const CutterProfile& cp, double x, double y) const;
  // Whether piece k's cutter (profiles, lowered by `drop`) reaches down to z over (x, y).
  bool reaches(uint32_t k, const std::vector<CutterProfile>& profiles, double drop, double x, double y,
               double z) const;
  // The least XY distance from (x, y) to piece k's axis path (a lower bound for an arc: to its whole circle).
  double axis_distance(uint32_t k, double x, double y) const;
  void keep(const Piece& p);
  size_t bin_of(double x, double y) const;

  GridSpec bins_;  // the bins as a grid
  double near_ = 0;
  std::vector<CutterProfile> profiles_, grown_;  // each cutter's, and grown by near_
  std::vector<Cutter> cutters_;  // the cutter of each profile (one profile per distinct cutter)
  std::vector<Piece> pieces_;
  std::vector<sweep::LineFrame> lines_;  // per piece: a line's frame, made once (unused for an arc)
  // Per bin, the moves that meet it, by their lowest tip ascending (rounded down to a float: never above the
  // tip), so that a query at z stops at the first above it.
  struct Entry {
    float lowest;
    uint32_t id;
  };
  std::vector<std::vector<Entry>> in_bin_;
};

}  // namespace rosmill::core::stock
