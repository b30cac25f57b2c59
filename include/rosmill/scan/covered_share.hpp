// How much of one point set another covers: the share of `queries` with a point of `cloud` within `radius` mm
// (a k-d tree). Registration's overlap (of the design by the scan) and fusion's check that a view meets the
// others both read it.
#pragma once
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::scan {

// 0 when either set is empty.
double covered_share(const std::vector<Vec3>& queries, const std::vector<Vec3>& cloud, double radius);

}  // namespace rosmill::core::scan
