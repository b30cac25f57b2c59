// gcode_bridge: the last job on `toolpath` (or a RunProgram goal's job) -> the program pipeline (post, machine
// limits, optionally LinuxCNC's rs274 as a judge) -> a G-code file in program_dir -> a controller (LinuxCNC, GRBL
// or a folder), run and watched by control::ProgramRun. `program_status` is published at status_rate while a
// program runs, with its view on `program_markers` and a diagnostic on /diagnostics. Services ~start, ~pause,
// ~resume, ~abort (std_srvs/Trigger) and the `run_program` action (feedback: the status; cancel aborts).
#include <actionlib/server/simple_action_server.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <mutex>

#include "rosmill/RunProgramAction.h"
#include "rosmill/control/program_run.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/finish_goal.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/program_status_board.hpp"

namespace rosmill::edge {
namespace {

using Clock = std::chrono::steady_clock;

class GcodeBridge {
 public:
  GcodeBridge(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh)
      : controller_(string_param(pnh, "controller", "file:///tmp/rosmill")),
        program_dir_(string_param(pnh, "program_dir", "/tmp/rosmill")),
        status_rate_(double_param(pnh, "status_rate", 10.0, 5.0, 100.0)),
        stall_timeout_(double_param(pnh, "stall_timeout", 60.0, 1.0, 3600.0)),
        board_(nh, string_param(pnh, "frame_id", "workpiece"), controller_),
        updater_(nh, pnh),
        action_(nh, "run_program", [this](const RunProgramGoalConstPtr& goal) { on_goal(goal); }, false) {
    post_.dialect = string_param(pnh, "dialect", "linuxcnc");
    gcode::find_dialect(post_.dialect);  // validates the name now
    post_.arcs = bool_param(pnh, "arcs", false);
    post_.decimals = int_param(pnh, "decimals", 3, 1, 6);
    checks_.rs274 = bool_param(pnh, "verify_rs274", true);
    const std::string machine = string_param(pnh, "machine", "");
    if (!machine.empty()) checks_.machine = gcode::load_machine_limits(machine);
    else if (!bool_param(pnh, "no_limits", false))
      throw Error("parameter machine", "is required (the machine limits file, config/machine.yaml); set no_limits "
                                       "to true to run programs without checking the machine's limits");
    controller_options_.reply_timeout_s = double_param(pnh, "reply_timeout", 10.0, 0.1, 600.0);
    controller_options_.dialect = post_.dialect;
    controller_options_.program_dir = program_dir_;
    control::open_controller(controller_, controller_options_);  // a malformed URI stops the node now
    make_program_dir();

    job_sub_ = nh.subscribe("toolpath", 1, &GcodeBridge::on_job, this);
    services_ = {pnh.advertiseService("start", &GcodeBridge::on_start, this),
                 pnh.advertiseService("pause", &GcodeBridge::on_pause, this),
                 pnh.advertiseService("resume", &GcodeBridge::on_resume, this),
                 pnh.advertiseService("abort", &GcodeBridge::on_abort, this)};
    updater_.setHardwareID(controller_);
    updater_.add("program", &board_, &ProgramStatusBoard::diagnose);
    timer_ = nh.createWallTimer(::ros::WallDuration(1.0 / status_rate_), &GcodeBridge::on_timer, this);
    action_.start();
  }

 private:
  void make_program_dir() {
    if (program_dir_.empty() || program_dir_.front() != '/')
      throw Error("parameter program_dir", "must be an absolute folder, got '" + program_dir_ + "'");
    std::error_code ec;
    std::filesystem::create_directories(program_dir_, ec);
    if (!std::filesystem::is_directory(program_dir_))
      throw Error("parameter program_dir", "cannot create the folder " + program_dir_ + ": " + ec.message());
    ::chmod(program_dir_.c_str(), 0755);  // a controller running as another user reads the programs from here
  }

  void on_job(const msg::ToolpathJob::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(job_mutex_);
    last_job_ = msg;
  }

  // The job through the program pipeline into program_dir; returns the file's path.
  std::string write_program(const msg::ToolpathJob& msg, const Job& job, gcode::Program& program) {
    if (job.empty()) throw Error("job", "has no toolpath (none received on the toolpath topic yet?)");
    gcode::PostOptions options = post_;
    options.title = "rosmill gcode_bridge: " + msg.toolpaths[0].strategy + ", setup " + msg.toolpaths[0].setup;
    program = gcode::prepare_program(job, options, checks_).program;
    const std::string path = program_dir_ + "/rosmill-" + std::to_string(::ros::WallTime::now().sec) + "-" +
                             std::to_string(++program_counter_) + ".ngc";
    gcode::write_program(path, program);
    ::chmod(path.c_str(), 0644);
    return path;
  }

  // Prepares and starts a run; returns the reason when it cannot. Blocks while the controller connects.
  std::string start_run(const msg::ToolpathJob& job, const std::string& uri, uint32_t from_line) {
    std::lock_guard<std::mutex> lock(run_mutex_);
    if (run_ && run_->active()) return "a program is running on " + board_.copy().controller + ": abort it first";
    run_.reset();
    const std::string url = uri.empty() ? controller_ : uri;
    try {
      const Job core_job = from_job_msg(job);
      gcode::Program program;
      const std::string path = write_program(job, core_job, program);
      control::SendOptions send;
      send.from_line = std::max<uint32_t>(from_line, 1);
      if (send.from_line > program.lines.size())
        throw Error("from_line", std::to_string(send.from_line) + " is past the program's " +
                                     std::to_string(program.lines.size()) + " lines");
      auto controller = control::open_controller(url, controller_options_);
      const gcode::MachineLimits* machine = checks_.machine ? &*checks_.machine : nullptr;
      board_.begin(url, path, program.lines.size(), program_placement(job, core_job, machine));
      run_ = std::make_unique<control::ProgramRun>(
          std::move(controller), program.lines, send, stall_timeout_,
          [this](const control::ControllerStatus& s, control::RunVerdict v) { board_.update(s, v); });
      ROS_INFO("gcode_bridge: %s: %zu lines on %s", path.c_str(), program.lines.size(), url.c_str());
    } catch (const std::exception& e) {
      board_.set_state(msg::ProgramStatus::ERROR, e.what());
      return e.what();
    }
    started_ = Clock::now();
    board_.started();
    return "";
  }

  // At status_rate while a program runs, once a second otherwise; diagnostics at their own period.
  void on_timer(const ::ros::WallTimerEvent&) {
    if (board_.running() || ++idle_ticks_ >= status_rate_) {
      idle_ticks_ = 0;
      board_.publish();
    }
    updater_.update();
  }

  // ------------------------------------------------------------------------------------------ commands

  // A command on the running program; returns the reason when it cannot.
  std::string command(const char* what, void (control::ProgramRun::*fn)()) {
    std::lock_guard<std::mutex> lock(run_mutex_);
    if (!run_ || !run_->active() || !board_.running()) return std::string("no program is running: nothing to ") + what;
    try {
      (run_.get()->*fn)();
    } catch (const std::exception& e) {
      return std::string(what) + ": " + e.what();
    }
    if (fn == &control::ProgramRun::abort) {
      board_.set_state(msg::ProgramStatus::ABORTED);  // the run's worker publishes nothing after its abort
      ROS_WARN("gcode_bridge: program aborted");
    }
    return "";
  }

  static bool reply(std_srvs::Trigger::Response& res, const std::string& why, const std::string& done) {
    res.success = why.empty();
    res.message = why.empty() ? done : why;
    return true;
  }

  bool on_start(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    msg::ToolpathJob::ConstPtr job;
    {
      std::lock_guard<std::mutex> lock(job_mutex_);
      job = last_job_;
    }
    if (!job) return reply(res, "no job received on the toolpath topic yet", "");
    return reply(res, start_run(*job, "", 1), "started " + board_.copy().program);
  }
  bool on_pause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return reply(res, command("pause", &control::ProgramRun::feed_hold), "feed hold");
  }
  bool on_resume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return reply(res, command("resume", &control::ProgramRun::resume), "resumed");
  }
  bool on_abort(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return reply(res, command("abort", &control::ProgramRun::abort), "aborted");
  }

  // ------------------------------------------------------------------------------------------ the action

  void on_goal(const RunProgramGoalConstPtr& goal) {
    RunProgramResult result;
    msg::ToolpathJob job = goal->job;
    if (job.toolpaths.empty()) {
      std::lock_guard<std::mutex> lock(job_mutex_);
      if (last_job_) job = *last_job_;
    }
    const std::string why = start_run(job, goal->controller, goal->from_line);
    if (!why.empty()) {
      result.message = why;
      // Not the board's status: that is the run before, which this goal did not start.
      result.status = refused_status(goal->controller.empty() ? controller_ : goal->controller, why);
      result.status.header.frame_id = board_.copy().header.frame_id;
      action_.setAborted(result, why);
      return;
    }
    ::ros::WallRate rate(status_rate_);
    bool cancelled = false;
    while (board_.running() && ::ros::ok()) {
      if (action_.isPreemptRequested() && !cancelled) {
        cancelled = true;
        const std::string abort_why = command("abort", &control::ProgramRun::abort);
        if (!abort_why.empty()) ROS_ERROR("gcode_bridge: cancel: %s", abort_why.c_str());
      }
      RunProgramFeedback fb;
      fb.status = board_.copy();
      action_.publishFeedback(fb);
      rate.sleep();
    }
    result.status = board_.copy();
    result.program = result.status.program;
    result.lines = result.status.total_lines;
    result.acknowledged_line = result.status.acknowledged_line;
    result.duration = std::chrono::duration<double>(Clock::now() - started_).count();
    result.success = result.status.state == msg::ProgramStatus::DONE;
    result.message = result.success ? "program done"
                                    : result.status.state_name + (result.status.last_error.empty()
                                                                      ? std::string()
                                                                      : ": " + result.status.last_error);
    finish_goal(action_, result, cancelled, result.success);
  }

  std::string controller_, program_dir_;
  double status_rate_, stall_timeout_;
  gcode::PostOptions post_;
  gcode::ProgramChecks checks_;
  control::ControllerOptions controller_options_;
  int program_counter_ = 0;
  int idle_ticks_ = 0;
  Clock::time_point started_;

  std::mutex job_mutex_;
  msg::ToolpathJob::ConstPtr last_job_;

  std::mutex run_mutex_;  // one start or command at a time
  std::unique_ptr<control::ProgramRun> run_;

  ProgramStatusBoard board_;
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
