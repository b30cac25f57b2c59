// A sphere moving along a line against one triangle: the first parameter at which it touches the triangle. What
// a tilted ball end mill's contact with a mesh comes down to: the ball is the same whatever the tool axis, so
// pushing it along the axis until it touches gives the exact cutter location, and the ball swept from far along
// the axis down to that contact also holds the shank of the same radius (Lauwers, Kiswanto and Kruth, "Five-axis
// tool paths on faceted models", CIRP Annals 2003, drop the tilted tool along its axis the same way).
//
// The centre runs c(t) = o + t d (d unit). The sphere of radius r touches the triangle where the distance from c(t)
// to it is r: on the face (the plane at distance r with the foot inside the triangle), on an edge (the cylinder of
// radius r about it, the foot within the edge) or at a corner (the sphere of radius r about it). The first of those
// is the contact.
#pragma once
#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

// The least t in [t_min, t_max] at which the sphere touches triangle (a, b, c); t_min itself when it already touches
// or overlaps it there; +infinity when it does not within the range. A degenerate triangle meets it by its edges
// and corners.
double sphere_sweep_triangle(const Vec3& o, const Vec3& d, double radius, const Vec3& a, const Vec3& b, const Vec3& c,
                             double t_min, double t_max);

}  // namespace rosmill::core
