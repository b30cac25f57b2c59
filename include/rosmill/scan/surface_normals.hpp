// Normals of a scanned surface, for point-to-plane ICP between views: the least-squares plane of each point's
// nearest neighbours (the eigenvector of their covariance with the least spread; Hoppe et al., "Surface
// reconstruction from unorganized points", 1992). Their sign is arbitrary, which the point-to-plane distance ignores.
#pragma once
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::scan {

// One unit normal per point from its `neighbours` nearest points; a point whose neighbours fit no plane gets
// +Z (it then pairs like a point-to-point match along Z only). Throws Error when there are too few points.
std::vector<Vec3> estimate_normals(const std::vector<Vec3>& points, int neighbours = 12);

}  // namespace rosmill::core::scan
