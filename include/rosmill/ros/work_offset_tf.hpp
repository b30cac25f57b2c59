// The program's work offset from tf: where the workpiece frame (as scan_registrar publishes it after a
// registration) sits in the frame of the machine's coordinates, as G54's origin and turn (gcode/work_offset.hpp).
// Read from the node's private parameters `work_offset_frame` (empty: none, the controller's G54 as it stands),
// `machine_frame` (default table), `max_tilt_deg` (0.05) and `transform_timeout` (s, 2). The bridge and the
// planner's plan_job (programs written with output_dir) share it.
#pragma once
#include <ros/node_handle.h>
#include <tf2_ros/buffer.h>

#include <optional>
#include <string>

#include "rosmill/gcode/work_offset.hpp"
#include "rosmill/ros/namespaces.hpp"

namespace rosmill::edge {

struct WorkOffsetSource {
  std::string machine_frame = "table", workpiece_frame;
  double max_tilt_deg = 0.05, transform_timeout = 2.0;

  // The work offset now, or none without a workpiece_frame; Error when tf has no transform or the part is tilted.
  std::optional<gcode::WorkOffset> now(const tf2_ros::Buffer* tf) const;
};

// Errors name the bad parameter.
WorkOffsetSource work_offset_source(const ::ros::NodeHandle& pnh);

}  // namespace rosmill::edge
