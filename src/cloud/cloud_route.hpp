// Internal pieces of the cloud plan (cloud_plan.cpp): the zigzag route of raster lines, its drop-cutter
// heights computed on both cores in chunks (progress and cancellation between chunks), the seed's buffer
// point interpolation, and progress sub-ranges.
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

// Raster lines joined end to start (forward, backward, ...) and sampled every `step` at most.
struct Route {
  std::vector<Vec2> xy;
  std::vector<uint8_t> corner;        // 1 at line ends: always kept as CL points
  std::vector<uint32_t> line_start;   // first sample of each line (the connector before it belongs to it)
  size_t lines() const { return line_start.size(); }
};

// Lines along direction `angle_deg` over the plan box [u0, u1] x v (u along the lines, v across), at the
// given v offsets, in the rotated frame; xy are world coordinates.
Route zigzag_route(double angle_deg, double u0, double u1, const std::vector<double>& v, double step);

// Plan-view extent of a box along the raster direction: u (along) and v (across).
void box_extent(const Box3& box, double angle_deg, double& u0, double& u1, double& v0, double& v1);

// Drop heights at every route sample (both cores), in chunks, reporting progress.
std::vector<double> route_drops(const CloudSurface& s, const Cutter& cutter, const Route& route,
                                const ProgressRange& progress);

// The seed's interpolation (3.3.3) over a run of fine CL samples [first, last]: keeps `first`, `last`, every
// corner, one sample per `interval` of length, and the buffer points where the step error exceeds `eps`.
// Appends kept indices to `kept` in order; returns how many were buffer points.
size_t buffer_points(const std::vector<Vec3>& cl, const std::vector<uint8_t>& corner, size_t first, size_t last,
                     double interval, double eps, std::vector<uint32_t>& kept);

// Removes middle points of straight (collinear, same-direction) runs of moves.
void drop_collinear(std::vector<Vec3>& pts);

}  // namespace rosmill::cloud_detail
