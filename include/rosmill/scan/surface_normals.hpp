// Normals of a scanned surface, for point-to-plane ICP between views: the least-squares plane of each point's
// nearest neighbours (the eigenvector of their covariance with the least spread; Hoppe et al., "Surface
// reconstruction from unorganized points", 1992). Their sign is arbitrary, which the point-to-plane distance ignores.
#pragma once
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::scan {

// One unit normal per point from its `neighbours` nearest points; a point whose neighbours fit no plane gets
// +Z (it then pairs like a point-to-point match along Z only). When `variation` is given, it receives each point's
// surface variation, the least spread over the total (Pauly, Gross & Kobbelt, "Efficient simplification of
// point-sampled surfaces", 2002): near 0 on a face, up to 1/3 where the neighbours straddle a step or an edge and
// the fitted normal is no face's. Throws Error when there are too few points.
std::vector<Vec3> estimate_normals(const std::vector<Vec3>& points, int neighbours = 12,
                                   std::vector<double>* variation = nullptr);

}  // namespace rosmill::core::scan
