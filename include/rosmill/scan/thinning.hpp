// Fewer points for the steps whose cost grows with them (global alignment, ICP), chosen without randomness so a
// run repeats exactly.
#pragma once
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::scan {

// Every k-th point, at most `limit` of them, spread over the whole input.
std::vector<Vec3> thin_evenly(const std::vector<Vec3>& points, size_t limit);

// One point (the centroid) per occupied voxel of `leaf` mm: an even density, where a scanner crowds its points
// on the surfaces it looks straight at. Throws Error when the leaf is too small for the cloud's extent.
std::vector<Vec3> thin_by_voxel(const std::vector<Vec3>& points, double leaf);

}  // namespace rosmill::core::scan
