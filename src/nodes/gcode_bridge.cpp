// gcode_bridge: the last job on `toolpath` (or a RunProgram goal's job) -> the program pipeline (post, machine
// limits, optionally LinuxCNC's rs274 as a judge) -> a G-code file in program_dir -> a controller (LinuxCNC, GRBL
// or a folder), run and watched by control::ProgramRun. `program_status` is published at status_rate while a
// program runs, with its view on `program_markers` and a diagnostic on /diagnostics. Services ~start, ~pause,
// ~resume, ~abort (std_srvs/Trigger) and the `run_program` action (feedback: the status; cancel aborts). With
// ~work_offset_frame (e.g. `workpiece`, published by scan_registrar) every program sets G54 to that frame's pose
// in ~machine_frame (G10 L2 P1). A 3+2 job (its toolpaths indexed) needs a trunnion machine file (~machine with
// `rotary:`): the post retracts to its safe Z before each indexing, and while the program runs the workpiece frame
// is published on tf in ~machine_frame as the controller turns A and C.
#include <actionlib/server/simple_action_server.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_listener.h>

#include <mutex>

#include "rosmill/RunProgramAction.h"
#include "rosmill/ros/finish_goal.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/program_runner.hpp"
#include "rosmill/ros/program_status_board.hpp"

namespace rosmill::edge {
namespace {

class GcodeBridge {
 public:
  GcodeBridge(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh)
      : settings_(runner_settings(pnh)),
        board_(nh, string_param(pnh, "frame_id", "workpiece"), settings_.controller, settings_.work_offset.machine_frame),
        tf_listener_(tf_),
        runner_(settings_, board_, &tf_),
        updater_(nh, pnh),
        action_(nh, "run_program", [this](const RunProgramGoalConstPtr& goal) { on_goal(goal); }, false) {
    job_sub_ = nh.subscribe("toolpath", 1, &GcodeBridge::on_job, this);
    services_ = {pnh.advertiseService("start", &GcodeBridge::on_start, this),
                 pnh.advertiseService("pause", &GcodeBridge::on_pause, this),
                 pnh.advertiseService("resume", &GcodeBridge::on_resume, this),
                 pnh.advertiseService("abort", &GcodeBridge::on_abort, this)};
    updater_.setHardwareID(settings_.controller);
    updater_.add("program", &board_, &ProgramStatusBoard::diagnose);
    timer_ = nh.createWallTimer(::ros::WallDuration(1.0 / settings_.status_rate), &GcodeBridge::on_timer, this);
    action_.start();
  }

 private:
  void on_job(const msg::ToolpathJob::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(job_mutex_);
    last_job_ = msg;
  }

  msg::ToolpathJob::ConstPtr last_job() {
    std::lock_guard<std::mutex> lock(job_mutex_);
    return last_job_;
  }

  // At status_rate while a program runs, once a second otherwise; diagnostics at their own period.
  void on_timer(const ::ros::WallTimerEvent&) {
    if (board_.running() || ++idle_ticks_ >= settings_.status_rate) {
      idle_ticks_ = 0;
      board_.publish();
    }
    updater_.update();
  }

  static bool reply(std_srvs::Trigger::Response& res, const std::string& why, const std::string& done) {
    res.success = why.empty();
    res.message = why.empty() ? done : why;
    return true;
  }

  bool on_start(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    const msg::ToolpathJob::ConstPtr job = last_job();
    if (!job) return reply(res, "no job received on the toolpath topic yet", "");
    return reply(res, runner_.start(*job, "", 1), "started " + board_.copy().program);
  }
  bool on_pause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return reply(res, runner_.pause(), "feed hold");
  }
  bool on_resume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return reply(res, runner_.resume(), "resumed");
  }
  bool on_abort(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return reply(res, runner_.abort(), "aborted");
  }

  void on_goal(const RunProgramGoalConstPtr& goal) {
    ProgramGoalHooks hooks;
    hooks.cancel_requested = [this] { return action_.isPreemptRequested(); };
    hooks.feedback = [this](const RunProgramFeedback& fb) { action_.publishFeedback(fb); };
    const msg::ToolpathJob::ConstPtr last = last_job();
    bool cancelled = false;
    const RunProgramResult result =
        run_program_goal(*goal, last ? *last : msg::ToolpathJob(), runner_, board_, hooks, cancelled);
    finish_goal(action_, result, cancelled, result.success);
  }

  RunnerSettings settings_;
  ProgramStatusBoard board_;
  tf2_ros::Buffer tf_;
  tf2_ros::TransformListener tf_listener_;
  ProgramRunner runner_;
  int idle_ticks_ = 0;
  std::mutex job_mutex_;
  msg::ToolpathJob::ConstPtr last_job_;
  ::ros::Subscriber job_sub_;
  std::vector<::ros::ServiceServer> services_;
  ::ros::WallTimer timer_;
  diagnostic_updater::Updater updater_;
  actionlib::SimpleActionServer<RunProgramAction> action_;
};

}  // namespace
}  // namespace rosmill::edge

int main(int argc, char** argv) {
  // Three threads: the status timer keeps its rate while a service waits for the controller to connect.
  return rosmill::edge::run_node<rosmill::edge::GcodeBridge>(argc, argv, "gcode_bridge", 3);
}
