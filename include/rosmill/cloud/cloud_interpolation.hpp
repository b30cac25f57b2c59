// The seed's interpolation (seed 004, 3.3.3, after Yau & Hsu): which cutter locations of a finely sampled raster
// line become the moves. For two kept CL points P1, P2 and a CL point Pi between them the step error is
//     ε = Pi.z - Pd.z,   Pd.z = P1.z - (P1.x - Pi.x)(P1.z - P2.z)/(P1.x - P2.x)
// (Pd: the chord's point above Pi; here x is the distance along the line, so any raster direction works). Where
// |ε| exceeds the allowed error, the worst Pi becomes a buffer point and both halves are checked again: a binary
// tree of buffer points.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill {

// ε of Pi against the chord P1-P2 (positive: Pi above the chord). Pi is projected onto the chord in plan view.
double step_error(const Vec3& p1, const Vec3& p2, const Vec3& pi);

// Over the run of CL samples [first, last] of `cl`: keeps `first`, `last`, every sample marked in `corner`, one
// sample per `interval` of plan length (the seed's CL spacing on level ground, 2R), and the buffer points that
// bring every sample's |ε| to at most `eps`. Appends the kept indices to `kept` in order; returns how many of
// them are buffer points.
size_t buffer_points(const std::vector<Vec3>& cl, const std::vector<uint8_t>& corner, size_t first, size_t last,
                     double interval, double eps, std::vector<uint32_t>& kept);

}  // namespace rosmill
