// What times a program on the machine: the limits and settings of its controller's trajectory planner, as
// LinuxCNC's configuration gives them ([TRAJ], [AXIS_x], [EMCMOT], [DISPLAY]; rosmill machine --from-ini reads them
// from a LinuxCNC ini file). Millimetres, degrees and seconds.
#pragma once
#include <map>
#include "rosmill/geometry/types.hpp"

namespace rosmill::core::gcode {

struct TrajectoryLimits {
  Vec3 max_velocity = Vec3::Zero();      // mm/s per axis ([AXIS_X] MAX_VELOCITY ...); zero: not limited
  Vec3 max_acceleration = Vec3::Zero();  // mm/s^2 per axis ([AXIS_X] MAX_ACCELERATION ...); zero: not limited
  double max_linear_velocity = 0;        // mm/s along the path ([TRAJ] MAX_LINEAR_VELOCITY); zero: not limited
  double max_linear_acceleration = 0;    // mm/s^2 along the path ([TRAJ] MAX_LINEAR_ACCELERATION); zero: not limited
  Vec2 rotary_velocity = Vec2::Zero();      // deg/s of A and C ([AXIS_A], [AXIS_C] MAX_VELOCITY)
  Vec2 rotary_acceleration = Vec2::Zero();  // deg/s^2 of A and C
  double servo_period = 0.001;           // s: the planner's cycle ([EMCMOT] SERVO_PERIOD, in ns there)
  int optimization_depth = 50;           // segments the planner looks ahead ([TRAJ] ARC_BLEND_OPTIMIZATION_DEPTH)
  bool arc_blend = true;                 // tangent arcs blend G64 corners ([TRAJ] ARC_BLEND_ENABLE)
  double tangent_kink_ratio = 0.1;       // a corner this gentle passes as tangent ([TRAJ] ARC_BLEND_KINK_RATIO)
  double max_feed_override = 1.0;        // the planner sizes blends for this feed override ([DISPLAY] MAX_FEED_OVERRIDE)
  double tool_change_seconds = 0;        // per M6 (the simulator's tool changer answers at once)
  // M6 first moves the tool here (machine coordinates, mm; [EMCIO] TOOL_CHANGE_POSITION) in one rapid.
  bool has_tool_change_position = false;
  Vec3 tool_change_position = Vec3::Zero();
  // After M3/M4 the first feed move waits until the spindle is at speed: it accelerates at this many rpm/s (zero:
  // at speed at once) and counts as at speed from this share of the commanded speed on (HAL's at-speed signal).
  double spindle_acceleration = 0;
  double spindle_at_speed_share = 1.0;
  double spindle_start_seconds = 0;      // more per M3/M4, whatever the speed
  // The controller's tool table: each tool's length offset (mm, its Z; [EMCIO] TOOL_TABLE), which G43 adds to the
  // program's Z. A move in machine coordinates (G53, the retract before the table turns) runs that much shorter or
  // longer than the program's numbers say. A tool not listed: no offset.
  std::map<int, double> tool_lengths;
  double tool_length(int tool) const {
    const auto at = tool_lengths.find(tool);
    return at == tool_lengths.end() ? 0.0 : at->second;
  }

  bool limited() const { return max_acceleration.maxCoeff() > 0; }
};

}  // namespace rosmill::core::gcode
