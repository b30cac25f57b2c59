// The tool axis of multi-axis finishing at one cutter location: the surface normal turned by a lead angle towards
// the direction of travel and a tilt angle to its side, kept inside a cone about the setup's +Z, and turned no
// faster along a pass than a rate allows. Lead and tilt as in five-axis CAM practice (Lauwers, Kiswanto and Kruth,
// "Five-axis tool paths on faceted models", CIRP Annals 2003): a ball end mill at a lead cuts off its tip, where
// the cutting speed is zero (Muslimin et al. name it as what multi-axis machining avoids).
#pragma once
#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

// The angle between two unit vectors, degrees, exact near 0 and 180 (atan2 of the cross and dot products).
double angle_between_deg(const Vec3& a, const Vec3& b);

// The normal n (unit) turned by `lead_deg` towards `travel` (its part along the surface) and by `tilt_deg` about
// the travel direction, to the travel's right seen from above the surface: cos(lead) n + sin(lead) f with tilt 0.
// With no travel along the surface (travel along n), n itself.
Vec3 lead_tilt_axis(const Vec3& n, const Vec3& travel, double lead_deg, double tilt_deg);

// The axis turned towards +Z, in the plane of both, until it lies within `cone_deg` of +Z; unchanged inside.
Vec3 within_cone(const Vec3& axis, double cone_deg);

// `from` turned towards `to` by at most `max_deg` (in the plane of both): `to` when it is that close.
Vec3 turn_towards(const Vec3& from, const Vec3& to, double max_deg);

}  // namespace rosmill::core
