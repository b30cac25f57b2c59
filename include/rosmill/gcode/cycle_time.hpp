// The cycle time of a program as LinuxCNC's trajectory planner runs it: one estimator for the CLI, the ROS action
// and the job report. It reads what will run (the posted program, arcs and feeds as written) and models the planner
// (LinuxCNC 2.9 tp.c and blendmath.c): per-axis velocity and acceleration limits along each move; under G64 P a
// tangent arc blends each corner within the tolerance (its speed limited by the normal acceleration it needs), a
// corner gentle enough passes as tangent, a rapid meeting a feed blends parabolically at half the acceleration;
// the look-ahead plans each segment's end speed so the machine can stop within the next `optimization_depth`
// segments; circular arcs keep part of the acceleration for the normal one; no segment runs shorter than a servo
// period. Spindle, coolant and tool changes wait for the motion queue to drain (a stop), plus the configured times.
#pragma once
#include <string>
#include <vector>

#include "rosmill/gcode/post.hpp"
#include "rosmill/gcode/trajectory_limits.hpp"

namespace rosmill::core::gcode {

struct CycleTime {
  double seconds = 0;         // the whole program
  double motion_seconds = 0;  // moving (the rest: tool changes, spindle starts, dwells)
  size_t segments = 0;        // the planner's segments: moves and blend arcs
  size_t stops = 0;           // where the machine comes to rest inside the program
};

// Throws Error naming `source` and the line for a program the G-code reader refuses.
CycleTime estimate_cycle_time(const std::vector<std::string>& program, const TrajectoryLimits& limits,
                              const std::string& source = {});

// A job posted as it would be written (post.hpp), then timed.
CycleTime estimate_cycle_time(const Job& job, const PostOptions& post, const TrajectoryLimits& limits);

}  // namespace rosmill::core::gcode
