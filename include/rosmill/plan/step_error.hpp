// Step-error sampling, the interpolation of Muslimin et al., "Direct NC Toolpath Generation from 3D Point Cloud
// Datasets" (after Yau & Hsu): which cutter locations of a finely sampled line become the moves. For two kept CL
// points P1, P2 and a CL point Pi between them the step error is
//     ε = Pi.z - Pd.z,   Pd.z = P1.z - (P1.x - Pi.x)(P1.z - P2.z)/(P1.x - P2.x)
// (Pd: the chord's point above Pi; here x is the distance along the line, so any raster direction works). Where
// |ε| exceeds the allowed error, the worst Pi becomes a buffer point and both halves are checked again: a binary
// tree of buffer points. Then every move between two kept locations is checked against the surface itself
// (Surface::sweep, the paper's "paths between grids are checked"), with a buffer point where it goes deepest.
// This is the raster's second sampling policy (raster.hpp, Sampling::StepError) besides chord refinement.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rosmill/plan/plan_support.hpp"

namespace rosmill::core {

// ε of Pi against the chord P1-P2 (positive: Pi above the chord). Pi is projected onto the chord in plan view.
double step_error(const Vec3& p1, const Vec3& p2, const Vec3& pi);

// Over the run of CL samples [first, last] of `cl`: keeps `first`, `last`, every sample marked in `corner`, one
// sample per `interval` of plan length (the CL spacing on level ground of Muslimin et al., 2R), and the buffer
// points that bring every sample's |ε| to at most `eps`. Appends the kept indices to `kept` in order; returns
// how many of them are buffer points.
size_t buffer_points(const std::vector<Vec3>& cl, const std::vector<uint8_t>& corner, size_t first, size_t last,
                     double interval, double eps, std::vector<uint32_t>& kept);

// The move from CL a to CL b (a already written) checked against the surface: while it reaches more than `t`
// into the cutter (the frame's drop cutter, grown by the allowance; CL = tip + allowance), a buffer point is
// dropped where it goes deepest and both halves are checked again. Appends the CL points after a, b last;
// returns how many were inserted.
size_t checked_move(const Surface& s, const PlanFrame& f, const Vec3& a, const Vec3& b, std::vector<Vec3>& out,
                    int depth = 0);

// What the policy did on one stretch.
struct StepErrorCounts {
  size_t samples = 0, buffers = 0, checked = 0;
};

// The policy on the stretch a-b: drops every sqrt(4 R t) (over level ground a ball's CL sags t/2 between two),
// buffer points to t/2, moves checked to t. Appends the CL points (a first, b last) to `out`.
void sample_step_error(const Surface& s, const PlanFrame& f, const Vec2& a, const Vec2& b, std::vector<Vec3>& out,
                       StepErrorCounts& counts);
// The fine sampling step of the policy for the frame's cutter and tolerance.
double step_error_spacing(const PlanFrame& f);

}  // namespace rosmill::core
