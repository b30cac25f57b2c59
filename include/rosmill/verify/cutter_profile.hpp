// The cutter's bottom as a height profile: how far above the tip the cutter's lower surface is at horizontal
// distance d from its axis. The material removal simulation sweeps this profile; the scallop check evaluates it.
#pragma once
#include <cmath>
#include <limits>

#include "rosmill/cutter/cutter.hpp"

namespace rosmill::verify {

// A bull nose is a flat disc of radius flat_radius widened by a torus corner of radius corner; a flat end has
// corner 0, a ball end has flat_radius 0. One formula covers all three.
struct CutterProfile {
  double radius = 3.0;       // R: half the diameter
  double corner = 0.0;       // r: corner radius (0 flat, R ball)
  double flat_radius = 3.0;  // R - r

  static CutterProfile of(const Cutter& c) {
    CutterProfile p;
    p.radius = c.radius();
    p.corner = c.type == CutterType::FlatEnd ? 0.0 : c.type == CutterType::BallEnd ? p.radius : c.corner_radius;
    p.flat_radius = p.radius - p.corner;
    return p;
  }

  // Height of the lower surface above the tip at distance d from the axis; +infinity outside the cutter.
  double height(double d) const {
    if (d > radius) return std::numeric_limits<double>::infinity();
    if (d <= flat_radius) return 0.0;
    const double e = d - flat_radius;
    return corner - std::sqrt(std::max(0.0, corner * corner - e * e));
  }

  // Theoretical scallop of parallel passes at stepover s on a flat floor: the profile height half-way between
  // two passes (for a ball: R - sqrt(R^2 - (s/2)^2)).
  double scallop(double stepover) const { return height(0.5 * stepover); }
};

}  // namespace rosmill::verify
