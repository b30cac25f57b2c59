// The bridge's program runs: a job through the one program pipeline (post, machine limits, optionally LinuxCNC's
// rs274 as a judge) into a G-code file in program_dir, a controller opened, a control::ProgramRun started and its
// status kept on the board; feed hold, resume and abort on the running program; and a RunProgram goal followed to
// its end. The settings are the node's parameters, read and checked once at start-up.
#pragma once
#include <ros/node_handle.h>

#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <tf2_ros/buffer.h>

#include "rosmill/RunProgramAction.h"
#include "rosmill/ToolpathJob.h"
#include "rosmill/control/program_run.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/ros/program_status_board.hpp"
#include "rosmill/ros/work_offset_tf.hpp"

namespace rosmill::edge {

struct RunnerSettings {
  std::string controller;   // the default controller URI
  std::string program_dir;  // absolute; created (0755) if missing
  double status_rate = 10.0, stall_timeout = 60.0;
  gcode::PostOptions post;
  gcode::ProgramChecks checks;
  control::ControllerOptions controller_options;
  // With a workpiece frame, every program sets G54 (G10 L2 P1) to where it sits on the machine at the run's start.
  WorkOffsetSource work_offset;
};

// The settings from the node's private parameters; an Error names a bad one. Opens the controller URI once (a
// malformed one stops the node at start-up) and makes the program folder.
RunnerSettings runner_settings(const ::ros::NodeHandle& pnh);

class ProgramRunner {
 public:
  // `tf` (may be null without a work_offset_frame) outlives the runner.
  ProgramRunner(RunnerSettings settings, ProgramStatusBoard& board, const tf2_ros::Buffer* tf = nullptr);

  // Prepares and starts a run of `job` on `uri` (empty: the default controller) from `from_line`; returns the
  // reason when it cannot. Blocks while the controller connects.
  std::string start(const msg::ToolpathJob& job, const std::string& uri, uint32_t from_line);
  // Commands on the running program; each returns the reason when it cannot.
  std::string pause() { return command("pause", &control::ProgramRun::feed_hold); }
  std::string resume() { return command("resume", &control::ProgramRun::resume); }
  std::string abort() { return command("abort", &control::ProgramRun::abort); }

  double seconds_running() const;
  const RunnerSettings& settings() const { return settings_; }

 private:
  std::string command(const char* what, void (control::ProgramRun::*fn)());
  std::string write_program(const msg::ToolpathJob& msg, const Job& job, gcode::Program& program,
                            std::optional<gcode::WorkOffset>& offset);

  RunnerSettings settings_;
  ProgramStatusBoard& board_;
  const tf2_ros::Buffer* tf_;
  int program_counter_ = 0;
  std::chrono::steady_clock::time_point started_;
  std::mutex run_mutex_;  // one start or command at a time
  std::unique_ptr<control::ProgramRun> run_;
};

struct ProgramGoalHooks {
  std::function<bool()> cancel_requested;
  std::function<void(const RunProgramFeedback&)> feedback;
};

// Follows one RunProgram goal (its job, or `last_job` when it carries none) from start to end: feedback at the
// status rate, a cancel aborts the program. A refused goal reports a refused status, not the run before it.
RunProgramResult run_program_goal(const RunProgramGoal& goal, const msg::ToolpathJob& last_job, ProgramRunner& runner,
                                  ProgramStatusBoard& board, const ProgramGoalHooks& hooks, bool& cancelled);

}  // namespace rosmill::edge
