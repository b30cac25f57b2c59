// Arc fitting: runs of linear feed moves that lie on a circle in a plane of constant Z become one circular
// move (G2/G3 in the XY plane). A run is accepted only when the arc stays within `tolerance` of the polyline
// it replaces: every vertex is within the tolerance of the circle after adding the chord's sagitta, the
// turning is one-way and the sweep under a full turn.
#pragma once
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::gcode {

struct ArcFitOptions {
  double tolerance = 0.005;     // mm
  int min_segments = 3;         // an arc replaces at least this many lines
  int max_segments = 1000;      // bounds the work per arc
  double max_radius = 5000.0;   // mm: flatter runs stay lines (huge radii are ill-conditioned in G-code)
  double min_radius = 0.05;     // mm
};

// A piece of a polyline: either `count` straight segments kept as lines, or one arc replacing them.
struct ArcPiece {
  int first = 0;     // index of the start vertex in the polyline
  int last = 0;      // index of the end vertex
  bool arc = false;  // false: the segments first..last stay lines
  bool clockwise = false;
  Vec2 centre = Vec2::Zero();
  double radius = 0.0;
};

// Splits polyline `points` (vertices, at least 2) into lines and arcs, in order, covering every segment once.
std::vector<ArcPiece> fit_arcs(const std::vector<Vec3>& points, const ArcFitOptions& options = {});

// Distance from point p (XY) to the arc from `from` to `to` around `centre` in the given direction.
double distance_to_arc(const Vec2& p, const Vec2& from, const Vec2& to, const Vec2& centre, bool clockwise);

}  // namespace rosmill::core::gcode
