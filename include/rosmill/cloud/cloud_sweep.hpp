// How deep the points of a cloud reach into a cutter that moves in a straight line: the check of the path
// between two cutter locations (Muslimin et al., section 3.3.2 case 2, "paths between grids are checked"), exact
// against every point under the swept footprint. Along a move the tip rises linearly and a point's distance from
// the axis is convex, so the depth of one point is a concave function of the position along the move: its maximum
// is at an end or where the point, seen from the cutter, is an edge contact (cutter/contact.hpp's edge_contact).
#pragma once
#include "rosmill/cloud/cloud_surface.hpp"

namespace rosmill::core {


// The cutter moving with its tip from a to b, against the points themselves (the support discs of sparse regions
// are the drop's conservative margin; here the data is checked: a ball's depth is then in closed form). Points
// that cannot go deeper than `floor` are skipped: `depth` is exact when it is above `floor`, and is `floor` (at 0)
// when no point goes deeper than that.
SweepHit sweep_depth(const CloudSurface& surface, const Cutter& cutter, const Vec3& a, const Vec3& b,
                     double floor = 0.0);

}  // namespace rosmill::core
