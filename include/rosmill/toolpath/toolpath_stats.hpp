// Figures of a toolpath (lengths), for reports, the CLI and the ROS statistics; and the time of one move from rest
// to rest. A program's time is the trajectory planner's (gcode/cycle_time.hpp), not a sum of moves.
#pragma once
#include <cstddef>

#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::core {

// Figures of a toolpath: lengths in mm.
struct ToolpathStats {
  size_t moves = 0;
  double cutting_length = 0.0;
  double rapid_length = 0.0;
};
ToolpathStats toolpath_stats(const Toolpath& tp);

// The time of one straight move of `length` along the unit vector `dir` at `feed` per minute that starts and ends
// at rest (an indexing of the rotary axes, a retract before it), accelerating and braking at the most the axes
// allow: along dir that is the least of a_i / |dir_i| over the moving axes (each axis's share of the path's
// acceleration stays within its own limit; zero: no limit). A move long enough to reach the feed takes
// length / v + v / a; a shorter one accelerates for half its length and brakes for the other half, 2 sqrt(length / a).
double move_seconds(double length, const Vec3& dir, double feed, const Vec3& max_acceleration);

}  // namespace rosmill::core
