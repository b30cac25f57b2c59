#include "rosmill/ros/work_offset_tf.hpp"

#include "rosmill/error.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/transform_wait.hpp"

namespace rosmill::edge {

std::optional<gcode::WorkOffset> WorkOffsetSource::now(const tf2_ros::Buffer* tf) const {
  if (workpiece_frame.empty()) return std::nullopt;
  const std::string where = "work offset from tf " + machine_frame + " -> " + workpiece_frame;
  if (!tf) throw Error(where, "the node has no tf listener");
  const Eigen::Matrix4d pose = to_mm_pose(
      wait_for_transform(*tf, machine_frame, workpiece_frame, ::ros::Time(0), transform_timeout, where));
  return gcode::work_offset_of_pose(pose, max_tilt_deg, where);
}

WorkOffsetSource work_offset_source(const ::ros::NodeHandle& pnh) {
  WorkOffsetSource s;
  s.machine_frame = string_param(pnh, "machine_frame", "table");
  s.workpiece_frame = string_param(pnh, "work_offset_frame", "");
  s.max_tilt_deg = double_param(pnh, "max_tilt_deg", 0.05, 0.0, 10.0);
  s.transform_timeout = double_param(pnh, "transform_timeout", 2.0, 0.0, 60.0);
  if (!s.workpiece_frame.empty() && s.workpiece_frame == s.machine_frame)
    throw Error("parameter work_offset_frame", "is the machine_frame itself ('" + s.machine_frame + "')");
  return s;
}

}  // namespace rosmill::edge
