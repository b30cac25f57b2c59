// The bridge's view of the program it runs, shared between the run's worker, the services, the action and the
// timer: the msg::ProgramStatus under one lock, published with its rviz view on every change of state and at the
// status rate, and summarised as a diagnostic.
#pragma once
#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "rosmill/ros/namespaces.hpp"
#include "rosmill/ProgramStatus.h"
#include "rosmill/control/program_run.hpp"
#include "rosmill/ros/program_status.hpp"

namespace rosmill::edge {

class ProgramStatusBoard {
 public:
  // `machine_frame`: where a 3+2 program's turning workpiece frame (`frame_id`) is published on tf as A and C move.
  ProgramStatusBoard(::ros::NodeHandle& nh, const std::string& frame_id, const std::string& controller,
                     const std::string& machine_frame = "machine");

  // A new program: its controller, file, length and where it sits; the state becomes CONNECTING.
  void begin(const std::string& controller, const std::string& program, size_t lines, const ProgramPlacement& place);
  // The program started: CONNECTING becomes RUNNING (unless the run's worker has already reported a state).
  void started();
  // A state the bridge knows better than the controller (running once started, an error, aborted).
  void set_state(uint8_t state, const std::string& error = "");
  // A polled controller status and the run's verdict on it.
  void update(const control::ControllerStatus& s, control::RunVerdict verdict);

  msg::ProgramStatus copy() const;
  bool running() const;  // connecting, running or paused
  void publish();
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& d);

 private:
  mutable std::mutex mutex_;
  msg::ProgramStatus status_;
  ProgramPlacement placement_;
  ::ros::Publisher status_pub_, marker_pub_;
  std::string machine_frame_;
  tf2_ros::TransformBroadcaster tf_;
  std::optional<geometry_msgs::TransformStamped> turning_;  // the workpiece on a turning table, when known
};

}  // namespace rosmill::edge
