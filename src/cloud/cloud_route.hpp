// Internal pieces of the cloud plan (cloud_plan.cpp): the zigzag of raster lines, the drop-cutter heights along
// it computed on both cores in chunks (progress and cancellation between chunks), the seed's buffer point
// interpolation (cloud_interpolation.hpp), the check of the moves between cutter locations, and progress sub-ranges.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/cloud/cloud_surface.hpp"
#include "rosmill/plan/strategy.hpp"

namespace rosmill::cloud_detail {

// Maps [0, 1] of one stage onto [lo, hi] of the caller's progress; throws Error("plan", "cancelled") when the
// callback asks to stop.
class ProgressRange {
 public:
  ProgressRange(const PlanProgress& p, double lo, double hi) : p_(p), lo_(lo), hi_(hi) {}
  void operator()(double f) const;
  ProgressRange sub(double a, double b) const { return ProgressRange(p_, lo_ + (hi_ - lo_) * a, lo_ + (hi_ - lo_) * b); }

 private:
  const PlanProgress& p_;
  double lo_, hi_;
};

// Raster lines joined end to start: line j runs along direction `angle_deg` at offset v[j] across it, from u0
// to u1 when j is even and back when it is odd; the step across joins it to the previous line's end.
class Zigzag {
 public:
  Zigzag(double angle_deg, double u0, double u1, std::vector<double> v, double step);
  size_t lines() const { return v_.size(); }
  // Samples of line j (world xy), at most `step` apart, the step across included. For j > 0 the first sample is
  // the previous line's last one, so the move onto the line belongs to it. corner = 1 at the ends of the step
  // across and of the line (always kept as cutter locations).
  void samples(size_t j, std::vector<Vec2>& xy, std::vector<uint8_t>& corner) const;
  // Samples of line j, not counting the previous line's last one.
  size_t sample_count(size_t j) const;

 private:
  Vec2 at(double u, double v) const { return du_ * u + dv_ * v; }
  Vec2 du_, dv_;
  double u0_, u1_, step_;
  std::vector<double> v_;
};

// The whole zigzag as one run of samples (the rough's levels walk it all).
struct Route {
  std::vector<Vec2> xy;
  std::vector<uint8_t> corner;
  size_t lines = 0;
};
Route whole_route(const Zigzag& z);

// Plan-view extent of a box along the raster direction: u (along) and v (across).
void box_extent(const Box3& box, double angle_deg, double& u0, double& u1, double& v0, double& v1);

// Drop heights at every route sample (both cores), in chunks, reporting progress.
std::vector<double> route_drops(const CloudSurface& s, const Cutter& cutter, const Route& route,
                                const ProgressRange& progress);

// The move from CL a to CL b (a already written) checked against the points: while some point would go more
// than `t` into the cutter (`cutter` grown by the allowance δ, CL = tip + δ), a buffer point is dropped where it
// goes deepest and both halves are checked again. Appends the CL points after a, b last; returns how many were
// inserted.
size_t checked_move(const CloudSurface& s, const Cutter& cutter, double delta, double t, const Vec3& a,
                    const Vec3& b, std::vector<Vec3>& out, int depth = 0);

// Removes middle points of straight (collinear, same-direction) runs of moves.
void drop_collinear(std::vector<Vec3>& pts);

}  // namespace rosmill::cloud_detail
