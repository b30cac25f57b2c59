// The space a ball-end mill sweeps along multi-axis moves, where the tool axis turns as the tip moves. Its flutes
// are a capsule: the segment from the ball's centre c (r above the tip along the axis) to t, r below the flutes'
// end, grown by the ball's radius r. Between two poses close together the flutes sweep the quad c0 c1 t1 t0 grown
// by r, which is two sphere-swept triangles (the Minkowski sum of a triangle and a ball: the points within r of
// it). A move is cut into steps that turn the axis so little that the arcs the ball's centre and the flute top
// follow stray from the steps' chords by at most `sagitta`; a straight move with a fixed axis is one step, exact.
//
// The capsule's round top reaches the flutes' end on the axis and stands inside their cylinder, which it leaves
// uncut at its rim (less removed, never more); the shank and holder above it are not swept: material they would pass
// through is a collision that the planner's clearance check refuses, not a cut.
//
// A grid of bins over XY lists the triangles whose footprint meets each bin. Queries: whether a point lies in the
// swept space (or within a distance of it), and the z-interval of a vertical line inside one triangle's sweep, what
// the stock's Z-dexels are clipped by.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::stock {

struct SweptTriangle {
  Vec3 v0, v1, v2;  // corners (two may coincide: a capsule)
  double r = 0;
  uint32_t move = 0;  // the index of the move that swept it
  Vec3 lo, hi;        // its box (the corners' grown by r): its footprint in XY and its height
};

// The part of the vertical line through (x, y) within r of the triangle: [lo, hi]; false when it misses it.
bool vertical_interval(const SweptTriangle& t, double x, double y, double& lo, double& hi);
// The distance from p to the triangle (not grown by r).
double distance_to_triangle(const SweptTriangle& t, const Vec3& p);

class MultiAxisSweep {
 public:
  // The sweep of the flutes between (tip0, axis0) and (tip1, axis1), the tip straight, the axis turning in
  // proportion (normalised): ball radius r, flute length `flutes` from the tip; steps whose arcs stray at most
  // `sagitta` mm from their chords, at most 256. Call index() after the last add.
  void add_move(const Vec3& tip0, const Vec3& axis0, const Vec3& tip1, const Vec3& axis1, double r, double flutes,
                double sagitta, uint32_t move);
  // Lists every triangle in its bins (again after more were added).
  void index();

  bool empty() const { return triangles_.empty(); }
  size_t size() const { return triangles_.size(); }
  const SweptTriangle& triangle(size_t k) const { return triangles_[k]; }
  size_t bytes() const;

  // Calls f(k) for every triangle whose footprint holds (x, y), in the order they were added (their height not
  // asked: a vertical line's).
  template <class F>
  void at(double x, double y, const F& f) const {
    const long b = bin_of(x, y);
    if (b < 0) return;
    for (uint32_t i = first_[size_t(b)]; i < first_[size_t(b) + 1]; ++i) {
      const SweptTriangle& t = triangles_[items_[i]];
      if (x >= t.lo.x() && x <= t.hi.x() && y >= t.lo.y() && y <= t.hi.y()) f(items_[i]);
    }
  }
  // True when p lies within r + `grow` of some triangle: swept (grow 0), or that near what was swept; `grow` at
  // most kMaxGrow.
  bool reaches(const Vec3& p, double grow = 0) const;
  static constexpr double kMaxGrow = 0.05;
  // How deep p lies inside the sweep: the most r - distance over the triangles (> 0 inside), and the move of that
  // triangle; -infinity where no footprint holds p.
  double depth(const Vec3& p,
               uint32_t* move = nullptr) const;  // mm: how far beyond its footprint a triangle is listed in the bins

 private:
  long bin_of(double x, double y) const;
  std::vector<SweptTriangle> triangles_;
  Vec2 origin_ = Vec2::Zero();
  double bin_ = 4.0;
  long nx_ = 0, ny_ = 0;
  std::vector<uint32_t> first_, items_;
};

}  // namespace rosmill::core::stock
