// An independent check of multi-axis toolpaths against a mesh, sharing no code with the planner: the exact
// distance from a point to the mesh of scan/mesh_distance.hpp (a k-d tree over the facets, Ericson's closest point
// on each near one), which planning does not use. The tool is a ball at the tip, a shank and a holder along its
// axis; each is sampled as points on its axis whose distance to the mesh must be at least the radius there, with the
// sampling's own shortfall bounded (a segment sampled every h may come h/2 closer between samples, which for a
// cylinder of radius r is at most r - sqrt(r^2 - h^2/4) deeper).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/scan/mesh_distance.hpp"
#include "rosmill/toolpath/toolpath.hpp"

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

struct ToolShape {
  double ball = 3, shank = 3, holder = 14;  // radii, mm
  double flute = 24, stick_out = 30, holder_length = 30;
};

// How deep the tool at `tip` along `axis` goes into the part: the most any of its sampled axis points lies closer
// to the mesh than its radius there (0 when clear). The ball centre is exact; the shank and holder sampled every
// `step` mm (see the top for the shortfall this leaves).
inline double tool_depth(const IndependentDistance& distance, const ToolShape& t, const Vec3& tip, const Vec3& axis,
                         double step = 0.5) {
  double depth = std::max(0.0, t.ball - distance(tip + t.ball * axis, t.ball + 1));
  for (double s = t.ball + step; s <= t.stick_out; s += step) {
    const double r = s <= t.flute ? t.ball : t.shank;
    depth = std::max(depth, r - distance(tip + s * axis, r + 1));
  }
  for (double s = t.stick_out; s <= t.stick_out + t.holder_length; s += step)
    depth = std::max(depth, t.holder - distance(tip + s * axis, t.holder + 1));
  return depth;
}

}  // namespace five_axis_check
