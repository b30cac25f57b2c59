// An independent drop-cutter, for checking the fast one (plan/mesh_surface) and the toolpaths built on it.
//
// It shares no code and no formula with cutter/contact.hpp: no facet, edge or vertex cases. A triangle is
// parametrised as p(s, t) = A + s (B - A) + t (C - A), s, t >= 0, s + t <= 1. The lowest tip that does not go
// into p is p.z - h(d), d the horizontal distance of p from the axis and h the cutter's height above its tip at
// that distance. p.z is affine in (s, t), h is convex and rising, d is convex: p.z - h(d) is concave, and so is
// its maximum over t for each s. The drop over one triangle is therefore found by a golden-section search over
// s of a golden-section search over t, each run until the bracket stops shrinking in double precision, on the
// part of the triangle that lies under the cutter's footprint. It is slow (thousands of evaluations per
// triangle) and meant only for tests and benchmarks.
#pragma once
#include <cstddef>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core {

// Highest tip height at axis (x, y) over the triangle (a, b, c); -infinity when no point of it lies under the
// footprint (horizontal distance <= the radius).
double reference_triangle_drop(const Cutter& cutter, double x, double y, const Vec3& a, const Vec3& b,
                               const Vec3& c);

// Highest tip height over every triangle of the mesh (-infinity when none is in reach). Each triangle is
// visited; the search runs only on those whose highest corner, lowered by the cutter's height at the distance
// of their XY box, could still beat the best so far.
double reference_drop(const Cutter& cutter, const Mesh& mesh, double x, double y);

// True when some point of the mesh lies inside the cutter (tip at `tip`) deeper than `depth` below the cutter's
// surface, i.e. when the cutter eroded by `depth` (radii smaller by it, tip higher by it) still meets the mesh.
// The depth is a distance, not a height: a cutter whose side just touches a wall is not in it, whereas its
// vertical drop there can jump by the wall's height (see ReferenceCheck::RimTie). Decided per triangle by a
// branch and bound on upper bounds that follow from the same concavity (reference_drop.cpp), far quicker than
// the drop itself.
bool reference_gouges(const Cutter& cutter, const Mesh& mesh, const Vec3& tip, double depth);

// How a drop z compares with the reference (both clamped to `floor`, the height of a cutter touching nothing).
enum class ReferenceCheck {
  Equal,    // within `tolerance` of the reference
  RimTie,   // not equal, but between the references of the cutter shrunk and grown by 1e-9 of its radius: a
            // feature lies exactly at the rim's distance, where the drop jumps (a ball beside an edge at distance
            // R touches it at its equator, a hair further it touches nothing) and the last bit of rounding decides
  Differs,  // wrong
};
ReferenceCheck check_drop(const Cutter& cutter, const Mesh& mesh, double x, double y, double z, double floor,
                          double tolerance);

}  // namespace rosmill::core
