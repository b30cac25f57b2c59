// The voxel grid filter: a cloud replaced by one point per occupied cube of side `leaf`, the centroid of the points
// in it -- PCL's VoxelGrid, computed in double and on every core. PCL's filter is single-threaded, works in float
// and indexes voxels with 32-bit integers; a fused scan of a few million points spent a quarter of its fusion time
// there. The cubes are those of PCL's grid (anchored at the cloud's lowest corner) and come out in its order
// (x fastest, then y, then z), so the result matches PCL's up to float rounding.
#pragma once
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

// Throws Error when `leaf` is not a positive number or too small for the cloud's extent (more than 2^62 cells),
// and when a point is not finite.
std::vector<Vec3> voxel_centroids(const std::vector<Vec3>& points, double leaf);

}  // namespace rosmill::core
