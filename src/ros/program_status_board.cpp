#include "rosmill/ros/program_status_board.hpp"

#include "rosmill/ros/convert.hpp"

namespace rosmill::edge {

ProgramStatusBoard::ProgramStatusBoard(::ros::NodeHandle& nh, const std::string& frame_id,
                                       const std::string& controller, const std::string& machine_frame)
    : machine_frame_(machine_frame) {
  status_.state = msg::ProgramStatus::IDLE;
  status_.state_name = status_state_name(status_.state);
  status_.controller = controller;
  status_.header.frame_id = frame_id;
  status_pub_ = nh.advertise<msg::ProgramStatus>("program_status", 1, true);
  marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("program_markers", 1, true);
}

void ProgramStatusBoard::begin(const std::string& controller, const std::string& program, size_t lines,
                               const ProgramPlacement& place) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    msg::ProgramStatus m;
    m.header.frame_id = status_.header.frame_id;
    m.controller = controller;
    m.program = program;
    m.total_lines = lines;
    status_ = m;
    placement_ = place;
    if (!place.trunnion) turning_.reset();
  }
  set_state(msg::ProgramStatus::CONNECTING);
}

void ProgramStatusBoard::started() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status_.state != msg::ProgramStatus::CONNECTING) return;
    status_.state = msg::ProgramStatus::RUNNING;
    status_.state_name = status_state_name(status_.state);
  }
  publish();
}

void ProgramStatusBoard::set_state(uint8_t state, const std::string& error) {
  if (state == msg::ProgramStatus::ERROR) ROS_ERROR("gcode_bridge: %s", error.c_str());
  {
    std::lock_guard<std::mutex> lock(mutex_);
    status_.state = state;
    status_.state_name = status_state_name(state);
    if (!error.empty()) status_.last_error = error;
  }
  publish();
}

void ProgramStatusBoard::update(const control::ControllerStatus& s, control::RunVerdict verdict) {
  uint8_t state = status_state(s.state);
  if (verdict == control::RunVerdict::Failed) state = msg::ProgramStatus::ERROR;
  if (verdict == control::RunVerdict::Finished) state = msg::ProgramStatus::DONE;
  uint8_t before;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    before = status_.state;
    const Eigen::Isometry3d workpiece = workpiece_in_machine(placement_, s);
    msg::ProgramStatus m = to_status_msg(s, state, workpiece.inverse());
    // A 3+2 program: the workpiece frame turns with the table, on tf for rviz (sent again with every publish, so
    // that it stays on tf after the program ends).
    if (placement_.trunnion && s.rotary_known)
      turning_ = to_transform_msg(machine_frame_, status_.header.frame_id, Eigen::Quaterniond(workpiece.linear()),
                                  to_metres(1.0) * workpiece.translation());
    m.header.frame_id = status_.header.frame_id;
    m.controller = status_.controller;
    m.program = status_.program;
    status_ = m;
  }
  if (state == before) return;
  if (state == msg::ProgramStatus::ERROR) ROS_ERROR("gcode_bridge: %s", s.error.c_str());
  ROS_INFO("gcode_bridge: program %s (line %zu of %zu)", status_state_name(state), s.current_line, s.total_lines);
  publish();  // every change at once, whatever the rate
}

msg::ProgramStatus ProgramStatusBoard::copy() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

bool ProgramStatusBoard::running() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_.state == msg::ProgramStatus::CONNECTING || status_.state == msg::ProgramStatus::RUNNING ||
         status_.state == msg::ProgramStatus::PAUSED;
}

void ProgramStatusBoard::publish() {
  msg::ProgramStatus m;
  geometry_msgs::Point anchor;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    status_.header.stamp = ::ros::Time::now();
    m = status_;
    anchor = placement_.anchor;
  }
  status_pub_.publish(m);
  marker_pub_.publish(status_markers(m, anchor));
  std::optional<geometry_msgs::TransformStamped> turning;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    turning = turning_;
  }
  if (turning) {
    turning->header.stamp = ::ros::Time::now();
    tf_.sendTransform(*turning);
  }
}

void ProgramStatusBoard::diagnose(diagnostic_updater::DiagnosticStatusWrapper& d) {
  const msg::ProgramStatus s = copy();
  using diagnostic_msgs::DiagnosticStatus;
  const uint8_t level = s.state == msg::ProgramStatus::ERROR ? DiagnosticStatus::ERROR
                        : s.state == msg::ProgramStatus::PAUSED || s.state == msg::ProgramStatus::ABORTED
                            ? DiagnosticStatus::WARN
                            : DiagnosticStatus::OK;
  d.summary(level, s.last_error.empty() ? s.state_name : s.state_name + ": " + s.last_error);
  d.add("controller", s.controller);
  d.add("program", s.program);
  d.add("line", std::to_string(s.current_line) + " / " + std::to_string(s.total_lines));
  d.add("acknowledged line", s.acknowledged_line);
}

}  // namespace rosmill::edge
