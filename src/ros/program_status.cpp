#include "rosmill/ros/program_status.hpp"

#include <algorithm>
#include <cstdio>

#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/markers.hpp"

namespace rosmill::edge {
namespace {

constexpr double kStatusHeight = 5.0;  // mm: the status line's text height
constexpr size_t kStatusChars = 40;    // "running  line 14964 / 14967  100%" and room to spare

// Where the status line begins: 10 mm beside the program's box on its +x side (the right of the bundled rviz view)
// and 15 mm over it, clear of the part, the tools drawn on it and the stock's legend below.
Vec3 status_left(const Box3& program) { return Vec3(program.max.x() + 10.0, program.min.y(), program.max.z() + 15.0); }

}  // namespace

uint8_t status_state(control::RunState s) {
  switch (s) {
    case control::RunState::Disconnected:
    case control::RunState::Idle: return msg::ProgramStatus::IDLE;
    case control::RunState::Running: return msg::ProgramStatus::RUNNING;
    case control::RunState::Paused: return msg::ProgramStatus::PAUSED;
    case control::RunState::Finished: return msg::ProgramStatus::DONE;
    case control::RunState::Alarm:
    case control::RunState::Error: return msg::ProgramStatus::ERROR;
  }
  return msg::ProgramStatus::ERROR;
}

const char* status_state_name(uint8_t state) {
  switch (state) {
    case msg::ProgramStatus::IDLE: return "idle";
    case msg::ProgramStatus::CONNECTING: return "connecting";
    case msg::ProgramStatus::RUNNING: return "running";
    case msg::ProgramStatus::PAUSED: return "paused";
    case msg::ProgramStatus::DONE: return "done";
    case msg::ProgramStatus::ERROR: return "error";
    case msg::ProgramStatus::ABORTED: return "aborted";
  }
  return "unknown";
}

msg::ProgramStatus refused_status(const std::string& controller, const std::string& why) {
  msg::ProgramStatus m;
  m.header.stamp = ::ros::Time::now();
  m.state = msg::ProgramStatus::ERROR;
  m.state_name = status_state_name(m.state);
  m.controller = controller;
  m.last_error = why;
  return m;
}

msg::ProgramStatus to_status_msg(const control::ControllerStatus& s, uint8_t state,
                               const Eigen::Isometry3d& machine_to_workpiece) {
  msg::ProgramStatus m;
  m.state = state;
  m.state_name = status_state_name(state);
  m.current_line = s.current_line;
  m.acknowledged_line = s.acknowledged_line;
  m.total_lines = s.total_lines;
  m.progress = s.total_lines > 0 ? float(std::min(1.0, double(s.acknowledged_line) / s.total_lines)) : 0.0f;
  m.position_known = s.position_known;
  if (s.position_known) m.position = to_point_msg(machine_to_workpiece * s.position);
  m.last_error = s.error;
  return m;
}

Eigen::Isometry3d workpiece_in_machine(const ProgramPlacement& place, const control::ControllerStatus& status) {
  if (!place.trunnion || !status.rotary_known) return place.machine_to_workpiece.inverse();
  return place.trunnion->table_in_machine(status.a, status.c).pose * place.workpiece_on_table;
}

ProgramPlacement program_placement(const msg::ToolpathJob& msg, const Job& job,
                                   const std::optional<gcode::WorkOffset>& g54,
                                   const std::optional<machine::Trunnion>& trunnion) {
  ProgramPlacement p;
  const bool indexed = std::any_of(job.begin(), job.end(), [](const core::Toolpath& tp) { return tp.indexed; });
  if (indexed && trunnion) {
    // 3+2: the program is in machine coordinates; the workpiece stands on the table and turns with it.
    p.trunnion = trunnion;
    p.workpiece_on_table = Eigen::Translation3d(from_point_msg(msg.workpiece_on_table));  // mm
    p.machine_to_workpiece = (trunnion->table_in_machine(job.front().a, job.front().c).pose * p.workpiece_on_table)
                                 .inverse();
    Box3 box;
    for (const core::Toolpath& tp : job) box.add(tp.bounds());
    p.anchor = to_point_msg(p.machine_to_workpiece * status_left(box));
    return p;
  }
  // The program is in the setup frame (the part re-fixtured); the status shows the tool on the part as it sits.
  Eigen::Isometry3d workpiece_in_setup = Eigen::Isometry3d::Identity();
  if (!msg.toolpaths.empty()) {
    const auto& q = msg.toolpaths[0].setup_rotation;
    Eigen::Quaterniond to_setup(q.w, q.x, q.y, q.z);
    if (to_setup.norm() < 1e-9) to_setup = Eigen::Quaterniond::Identity();
    workpiece_in_setup.linear() = to_setup.normalized().toRotationMatrix();
    workpiece_in_setup.translation() = from_vector_msg(msg.toolpaths[0].setup_translation);
  }
  const Eigen::Isometry3d program_on_machine(g54 ? g54->pose() : Eigen::Matrix4d::Identity());
  p.machine_to_workpiece = workpiece_in_setup.inverse() * program_on_machine.inverse();
  Box3 box;
  for (const core::Toolpath& tp : job) box.add(tp.bounds());
  p.anchor = to_point_msg(workpiece_in_setup.inverse() * status_left(box));
  return p;
}

visualization_msgs::MarkerArray status_markers(const msg::ProgramStatus& status, const geometry_msgs::Point& anchor) {
  visualization_msgs::MarkerArray array;
  char line[160];
  std::snprintf(line, sizeof line, "%s  line %u / %u  %.0f%%", status.state_name.c_str(), status.current_line,
                status.total_lines, 100.0 * status.progress);
  std::string words = line;
  if (!status.last_error.empty()) words += "\n" + status.last_error.substr(0, 120);
  visualization_msgs::Marker text =
      text_from_left(status.header, "program", 0, from_point_msg(anchor), words, kStatusHeight, kStatusChars);
  const bool bad = status.state == msg::ProgramStatus::ERROR || status.state == msg::ProgramStatus::ABORTED;
  text.color = bad ? rgba(1.0f, 0.3f, 0.3f) : rgba(1.0f, 1.0f, 1.0f);
  array.markers.push_back(text);

  visualization_msgs::Marker tip = base_marker(status.header, "program", 1, visualization_msgs::Marker::SPHERE);
  tip.action = status.position_known ? visualization_msgs::Marker::ADD : visualization_msgs::Marker::DELETE;
  tip.pose.position = status.position;
  tip.scale.x = tip.scale.y = tip.scale.z = 0.004;
  tip.color = rgba(1.0f, 0.9f, 0.1f);
  array.markers.push_back(tip);
  return array;
}

}  // namespace rosmill::edge
