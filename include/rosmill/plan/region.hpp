// A region of the XY plane where the cutter axis may go (raster finishing "only here"): closed polygons, inside
// by the even-odd rule, so that a loop inside a loop is a hole. Made from a contour (slicing) or from a patch of
// the segmentation.
#pragma once
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/segment/surface_patches.hpp"

namespace rosmill::core {

using Region = std::vector<std::vector<Vec2>>;

// True when p lies inside an odd number of the region's loops.
bool inside_region(const Region& region, const Vec2& p);

// The XY outline of a patch (phase 1 patch or a phase 2 segment's shape): its closed boundary loops projected
// on XY. Meant for a patch the +Z setup reaches, whose projection does not fold over itself. Throws Error when
// the patch has no closed loop.
Region patch_region(const Mesh& mesh, const segment::Patch& patch);

}  // namespace rosmill::core
