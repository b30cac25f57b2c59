// The controller's status (core, mm, machine coordinates) as a msg::ProgramStatus (m, program coordinates) and as an
// rviz view: the tool where the controller says it is and a line of text with the state and the line.
#pragma once
#include <optional>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>

#include "rosmill/ros/namespaces.hpp"
#include "rosmill/ProgramStatus.h"
#include "rosmill/ToolpathJob.h"
#include "rosmill/control/controller.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/toolpath/job.hpp"

namespace rosmill::edge {

// The message state of a run: the controller's state, unless the bridge knows better (aborted, connecting).
uint8_t status_state(control::RunState s);
const char* status_state_name(uint8_t state);

// The status a refused run reports: ERROR with the reason, nothing run (progress 0), whatever ran before.
msg::ProgramStatus refused_status(const std::string& controller, const std::string& why);

// `machine_to_workpiece` (mm) takes the controller's machine position to the workpiece frame: minus the work
// offset (config/machine.yaml), then back from the setup frame the program was posted in.
msg::ProgramStatus to_status_msg(const control::ControllerStatus& status, uint8_t state,
                               const Eigen::Isometry3d& machine_to_workpiece);

// Where a posted job sits for the status view: the transform from the controller's machine position (mm) to the
// workpiece frame (minus the work offset, then back from the setup frame the job was planned in) and the anchor
// of the status text (m: where its line begins, 10 mm beside the job's extent on +x and 15 mm above its top).
struct ProgramPlacement {
  Eigen::Isometry3d machine_to_workpiece = Eigen::Isometry3d::Identity();
  geometry_msgs::Point anchor;
  // A 3+2 job on a trunnion: the table turns the workpiece with A and C, so the transform follows them
  // (machine_to_workpiece_at) and the workpiece frame moves on tf.
  std::optional<machine::Trunnion> trunnion;
  Eigen::Isometry3d workpiece_on_table = Eigen::Isometry3d::Identity();  // mm
};
// The workpiece frame in the machine frame (mm) with the table where the controller says A and C are; the fixed
// placement without a trunnion or before A and C are known.
Eigen::Isometry3d workpiece_in_machine(const ProgramPlacement& place, const control::ControllerStatus& status);
// `msg` gives the setup the job was planned in, `job` (the same job, converted) its extent, `g54` where the
// program's origin is on the machine (none: the machine's origin).
ProgramPlacement program_placement(const msg::ToolpathJob& msg, const Job& job,
                                   const std::optional<gcode::WorkOffset>& g54,
                                   const std::optional<machine::Trunnion>& trunnion = std::nullopt);

// Namespace "program": a TEXT_VIEW_FACING line ("running  line 12 / 40  30%") that begins at `anchor` (m) and,
// when the position is known, a SPHERE at the tool tip.
visualization_msgs::MarkerArray status_markers(const msg::ProgramStatus& status, const geometry_msgs::Point& anchor);

}  // namespace rosmill::edge
