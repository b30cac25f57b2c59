// Distances for checking multi-axis toolpaths against a mesh with no code of the planner's: the exact distance from
// a point to the mesh of scan/mesh_distance.hpp (a k-d tree over the facets, Ericson's closest point on each near
// one), which planning does not use. The whole tool along the moves: verify/tool_clearance.hpp, on the same.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/scan/mesh_distance.hpp"

namespace five_axis_check {

using rosmill::core::Vec3;
using rosmill::core::scan::closest_on_triangle;

// The distance from p to the mesh; `beyond` when it is farther than that.
class IndependentDistance {
 public:
  explicit IndependentDistance(const rosmill::core::Mesh& mesh) : distance_(mesh) {}
  double operator()(const Vec3& p, double beyond = INFINITY) const {
    rosmill::core::scan::SurfaceDistance d;
    if (!std::isfinite(beyond)) return std::abs(distance_.query(p).signed_distance);
    return distance_.query_within(p, beyond, d) ? std::abs(d.signed_distance) : beyond;
  }

 private:
  rosmill::core::scan::MeshDistance distance_;
};

}  // namespace five_axis_check
