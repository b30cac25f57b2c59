// Figures of a toolpath (lengths and an estimate of the time), for reports, the CLI and the ROS statistics.
#pragma once
#include <cstddef>

#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::core {

// Figures of a toolpath: lengths in mm, time in seconds at the moves' feeds (rapids at `rapid_feed`).
struct ToolpathStats {
  size_t moves = 0;
  double cutting_length = 0.0;
  double rapid_length = 0.0;
  double estimated_seconds = 0.0;
};
// With `max_acceleration` (mm/s^2 per axis; zero: unlimited, the time at the feeds alone) each move is timed with
// a trapezoidal velocity profile that starts and ends at rest (move_seconds).
ToolpathStats toolpath_stats(const Toolpath& tp, double rapid_feed = 5000.0,
                             const Vec3& max_acceleration = Vec3::Zero());

// The time of one straight move of `length` mm along the unit vector `dir` at `feed` mm/min, accelerating and
// braking at the most the axes allow: along dir that is the least of a_i / |dir_i| over the moving axes (each
// axis's share of the path's acceleration stays within its own limit). Exact stop between moves (every move starts
// and ends at rest, as LinuxCNC's G61 runs them): blending (G64) only makes a real run faster, so the estimate is
// an upper bound. A move long enough to reach the feed takes length / v + v / a; a shorter one accelerates for
// half its length and brakes for the other half, 2 sqrt(length / a).
double move_seconds(double length, const Vec3& dir, double feed, const Vec3& max_acceleration);

}  // namespace rosmill::core
