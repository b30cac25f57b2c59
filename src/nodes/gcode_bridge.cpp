// gcode_bridge: the last job on `toolpath` (or a RunProgram goal's job) -> the post-processor (dialect, machine
// limits, optionally LinuxCNC's rs274 as a judge) -> a G-code file in program_dir -> the controller driver
// (control::open_controller: LinuxCNC, GRBL or a folder). While a program runs, a worker thread polls the
// controller and `program_status` (ProgramStatusMsg) is published at status_rate (>= 5 Hz), with its view on
// `program_markers` and a diagnostic on /diagnostics. Services ~start, ~pause, ~resume, ~abort (std_srvs/Trigger)
// and the `run_program` action (feedback: the status; cancel aborts the program on the controller).
#include <actionlib/server/simple_action_server.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <sys/stat.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>

#include "rosmill/RunProgramAction.h"
#include "rosmill/control/controller.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/gcode/rs274_check.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/finish_goal.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/program_status.hpp"

namespace rosmill::edge {
namespace {

using Clock = std::chrono::steady_clock;

// A posted program, checked and written, ready for a controller.
struct PreparedProgram {
  gcode::Program program;
  std::string path;
  Eigen::Isometry3d machine_to_workpiece = Eigen::Isometry3d::Identity();  // mm, for the reported position
  geometry_msgs::Point anchor;  // m, above the part: where rviz shows the status text
};

class GcodeBridge {
 public:
  GcodeBridge(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh)
      : controller_(string_param(pnh, "controller", "file:///tmp/rosmill")),
        program_dir_(string_param(pnh, "program_dir", "/tmp/rosmill")),
        status_rate_(double_param(pnh, "status_rate", 10.0, 5.0, 100.0)),
        stall_timeout_(double_param(pnh, "stall_timeout", 60.0, 1.0, 3600.0)),
        verify_rs274_(bool_param(pnh, "verify_rs274", true)),
        updater_(nh, pnh),
        action_(nh, "run_program", [this](const RunProgramGoalConstPtr& goal) { on_goal(goal); }, false) {
    post_.dialect = string_param(pnh, "dialect", "linuxcnc");
    gcode::find_dialect(post_.dialect);  // validates the name now
    post_.arcs = bool_param(pnh, "arcs", false);
    post_.decimals = int_param(pnh, "decimals", 3, 1, 6);
    controller_options_.reply_timeout_s = double_param(pnh, "reply_timeout", 10.0, 0.1, 600.0);
    controller_options_.dialect = post_.dialect;
    controller_options_.program_dir = program_dir_;
    const std::string machine = string_param(pnh, "machine", "");
    if (!machine.empty()) {
      limits_ = gcode::load_machine_limits(machine);
      has_limits_ = true;
    } else {
      ROS_WARN("gcode_bridge: no machine parameter: programs are not checked against the machine's limits");
    }
    open_controller(controller_, controller_options_);  // a malformed URI stops the node now, not at the first run
    make_program_dir();

    status_.state = ProgramStatusMsg::IDLE;
    status_.state_name = status_state_name(status_.state);
    status_.controller = controller_;
    status_.header.frame_id = string_param(pnh, "frame_id", "workpiece");
    status_pub_ = nh.advertise<ProgramStatusMsg>("program_status", 1, true);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("program_markers", 1, true);
    job_sub_ = nh.subscribe("toolpath", 1, &GcodeBridge::on_job, this);
    services_ = {pnh.advertiseService("start", &GcodeBridge::on_start, this),
                 pnh.advertiseService("pause", &GcodeBridge::on_pause, this),
                 pnh.advertiseService("resume", &GcodeBridge::on_resume, this),
                 pnh.advertiseService("abort", &GcodeBridge::on_abort, this)};
    updater_.setHardwareID(controller_);
    updater_.add("program", this, &GcodeBridge::diagnose);
    timer_ = nh.createWallTimer(::ros::WallDuration(1.0 / status_rate_), &GcodeBridge::on_timer, this);
    action_.start();
  }

  ~GcodeBridge() {
    // A sender that goes away mid-program would leave the machine half way: abort what runs (best effort).
    stop_.store(true);
    if (worker_.joinable()) worker_.join();
    std::lock_guard<std::mutex> lock(controller_mutex_);
    if (ctl_) {
      try {
        ctl_->abort();
        ctl_->disconnect();
      } catch (const std::exception& e) {
        ROS_ERROR("gcode_bridge: abort at shutdown: %s", e.what());
      }
    }
  }

 private:
  // ------------------------------------------------------------------------------------------ preparing a run

  void make_program_dir() {
    if (program_dir_.empty() || program_dir_.front() != '/')
      throw Error("parameter program_dir", "must be an absolute folder, got '" + program_dir_ + "'");
    std::error_code ec;
    std::filesystem::create_directories(program_dir_, ec);
    if (!std::filesystem::is_directory(program_dir_))
      throw Error("parameter program_dir", "cannot create the folder " + program_dir_ + ": " + ec.message());
    ::chmod(program_dir_.c_str(), 0755);  // a controller running as another user reads the programs from here
  }

  void on_job(const ToolpathJobMsg::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(job_mutex_);
    last_job_ = msg;
  }

  // Posts, checks and writes the job; throws Error naming what is wrong.
  PreparedProgram prepare(const ToolpathJobMsg& msg) {
    if (msg.toolpaths.empty()) throw Error("job", "has no toolpath (none received on the toolpath topic yet?)");
    const Job job = from_job_msg(msg);
    PreparedProgram p;
    gcode::PostOptions options = post_;
    options.title = "rosmill gcode_bridge: " + msg.toolpaths[0].strategy + ", setup " + msg.toolpaths[0].setup;
    p.program = gcode::post(job, options);
    if (has_limits_) gcode::require_within_limits(p.program.lines, limits_);
    if (verify_rs274_) {
      const gcode::VerifyReport report =
          gcode::compare_with_job(p.program, job, gcode::run_rs274(p.program.lines), options.arc_tolerance);
      if (!report.ok) throw Error("rs274 verification", report.problem);
    }
    p.path = program_dir_ + "/rosmill-" + std::to_string(::ros::WallTime::now().sec) + "-" +
             std::to_string(++program_counter_) + ".ngc";
    gcode::write_program(p.path, p.program);
    ::chmod(p.path.c_str(), 0644);
    // The program is in the setup frame (the part re-fixtured); the status shows the tool on the part as it sits.
    const auto& q = msg.toolpaths[0].setup_rotation;
    Eigen::Quaterniond to_setup(q.w, q.x, q.y, q.z);
    if (to_setup.norm() < 1e-9) to_setup = Eigen::Quaterniond::Identity();
    p.machine_to_workpiece = Eigen::Isometry3d(to_setup.normalized().conjugate()) *
                             Eigen::Translation3d(has_limits_ ? Vec3(-limits_.work_offset) : Vec3::Zero());
    Box3 box;
    for (const Toolpath& tp : job) box.add(tp.bounds());
    const Vec3 centre = 0.5 * (box.min + box.max);
    p.anchor = to_point_msg(p.machine_to_workpiece.linear() * Vec3(centre.x(), centre.y(), box.max.z() + 15.0));
    return p;
  }

  // Prepares and starts a run; returns the reason when it cannot. Blocks while the controller connects.
  std::string start_run(const ToolpathJobMsg& job, const std::string& uri, uint32_t from_line) {
    std::lock_guard<std::mutex> start_lock(start_mutex_);
    if (running()) return "a program is running on " + status_copy().controller + ": abort it first";
    if (worker_.joinable()) worker_.join();
    const std::string url = uri.empty() ? controller_ : uri;
    PreparedProgram prepared;
    try {
      prepared = prepare(job);
      const size_t first = std::max<uint32_t>(from_line, 1);
      if (first > prepared.program.lines.size())
        throw Error("from_line", std::to_string(first) + " is past the program's " +
                                     std::to_string(prepared.program.lines.size()) + " lines");
      std::unique_ptr<control::Controller> ctl = control::open_controller(url, controller_options_);
      set_state(ProgramStatusMsg::CONNECTING, url, prepared);
      ctl->connect();
      control::SendOptions send;
      send.from_line = first;
      ctl->start(prepared.program.lines, send);
      {
        std::lock_guard<std::mutex> lock(controller_mutex_);
        ctl_ = std::move(ctl);
      }
    } catch (const std::exception& e) {
      fail(e.what());
      return e.what();
    }
    ROS_INFO("gcode_bridge: %s: %zu lines on %s", prepared.path.c_str(), prepared.program.lines.size(), url.c_str());
    aborted_.store(false);
    stop_.store(false);
    started_ = Clock::now();
    set_state(ProgramStatusMsg::RUNNING, url, prepared);
    worker_ = std::thread(&GcodeBridge::watch, this);
    return "";
  }

  // ------------------------------------------------------------------------------------------ the running program

  // Polls the controller until the program ends, fails, stalls or is aborted.
  void watch() {
    control::ControllerStatus previous;
    auto last_change = Clock::now();
    while (!stop_.load()) {
      control::ControllerStatus s;
      {
        // aborted_ is set under this lock once the abort went out: no poll after it, and abort_run() has the
        // controller until it has published the final status.
        std::lock_guard<std::mutex> lock(controller_mutex_);
        if (!ctl_ || aborted_.load()) break;
        s = ctl_->poll(0.02);
      }
      const bool moved = s.acknowledged_line != previous.acknowledged_line || s.current_line != previous.current_line ||
                         (s.position - previous.position).norm() > 1e-6 || s.state != previous.state;
      if (moved || s.state == control::RunState::Paused) last_change = Clock::now();
      uint8_t state = status_state(s.state);
      if (s.state == control::RunState::Running &&
          std::chrono::duration<double>(Clock::now() - last_change).count() > stall_timeout_) {
        s.error = "no progress for " + std::to_string(stall_timeout_) + " s at program line " +
                  std::to_string(s.current_line);
        state = ProgramStatusMsg::ERROR;
      } else if (state == ProgramStatusMsg::IDLE) {  // disconnected or idle without finishing
        if (s.error.empty()) s.error = std::string("the controller went ") + control::run_state_name(s.state);
        state = ProgramStatusMsg::ERROR;
      }
      update_status(s, state);
      if (state == ProgramStatusMsg::DONE || state == ProgramStatusMsg::ERROR) break;
      previous = s;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    release_controller();
  }

  void release_controller() {
    std::lock_guard<std::mutex> lock(controller_mutex_);
    if (!ctl_) return;
    try {
      ctl_->disconnect();
    } catch (const std::exception& e) {
      ROS_WARN("gcode_bridge: disconnect: %s", e.what());
    }
    ctl_.reset();
  }

  bool running() {
    std::lock_guard<std::mutex> lock(status_mutex_);
    return status_.state == ProgramStatusMsg::CONNECTING || status_.state == ProgramStatusMsg::RUNNING ||
           status_.state == ProgramStatusMsg::PAUSED;
  }

  ProgramStatusMsg status_copy() {
    std::lock_guard<std::mutex> lock(status_mutex_);
    return status_;
  }

  void set_state(uint8_t state, const std::string& url, const PreparedProgram& p) {
    {
      std::lock_guard<std::mutex> lock(status_mutex_);
      status_.state = state;
      status_.state_name = status_state_name(state);
      status_.controller = url;
      status_.program = p.path;
      status_.total_lines = p.program.lines.size();
      status_.current_line = status_.acknowledged_line = 0;
      status_.progress = 0;
      status_.position_known = false;
      status_.last_error.clear();
      machine_to_workpiece_ = p.machine_to_workpiece;
      anchor_ = p.anchor;
    }
    publish_status();
  }

  void update_status(const control::ControllerStatus& s, uint8_t state) {
    uint8_t before;
    {
      std::lock_guard<std::mutex> lock(status_mutex_);
      if (aborted_.load()) return;  // abort_run() has the last word
      before = status_.state;
      ProgramStatusMsg m = to_status_msg(s, state, machine_to_workpiece_);
      m.header.frame_id = status_.header.frame_id;
      m.controller = status_.controller;
      m.program = status_.program;
      status_ = m;
    }
    if (state != before) {
      if (state == ProgramStatusMsg::ERROR) ROS_ERROR("gcode_bridge: %s", s.error.c_str());
      ROS_INFO("gcode_bridge: program %s (line %zu of %zu)", status_state_name(state), s.current_line, s.total_lines);
      publish_status();  // every change at once, whatever the rate
    }
  }

  void fail(const std::string& why) {
    ROS_ERROR("gcode_bridge: %s", why.c_str());
    {
      std::lock_guard<std::mutex> lock(status_mutex_);
      status_.state = ProgramStatusMsg::ERROR;
      status_.state_name = status_state_name(status_.state);
      status_.last_error = why;
    }
    publish_status();
  }

  void publish_status() {
    ProgramStatusMsg m;
    geometry_msgs::Point anchor;
    {
      std::lock_guard<std::mutex> lock(status_mutex_);
      status_.header.stamp = ::ros::Time::now();
      m = status_;
      anchor = anchor_;
    }
    status_pub_.publish(m);
    marker_pub_.publish(status_markers(m, anchor));
  }

  // At status_rate while a program runs, once a second otherwise; diagnostics at their own period.
  void on_timer(const ::ros::WallTimerEvent&) {
    if (running() || ++idle_ticks_ >= status_rate_) {
      idle_ticks_ = 0;
      publish_status();
    }
    updater_.update();
  }

  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& d) {
    const ProgramStatusMsg s = status_copy();
    using diagnostic_msgs::DiagnosticStatus;
    const uint8_t level = s.state == ProgramStatusMsg::ERROR ? DiagnosticStatus::ERROR
                          : s.state == ProgramStatusMsg::PAUSED || s.state == ProgramStatusMsg::ABORTED
                              ? DiagnosticStatus::WARN
                              : DiagnosticStatus::OK;
    d.summary(level, s.last_error.empty() ? s.state_name : s.state_name + ": " + s.last_error);
    d.add("controller", s.controller);
    d.add("program", s.program);
    d.add("line", std::to_string(s.current_line) + " / " + std::to_string(s.total_lines));
    d.add("acknowledged line", s.acknowledged_line);
  }

  // ------------------------------------------------------------------------------------------ commands

  // Runs a controller command on the running program; returns the reason when it cannot.
  std::string command(const char* what, void (control::Controller::*fn)()) {
    std::lock_guard<std::mutex> lock(controller_mutex_);
    return command_locked(what, fn);
  }
  std::string command_locked(const char* what, void (control::Controller::*fn)()) {
    if (!ctl_ || !running()) return std::string("no program is running: nothing to ") + what;
    try {
      (ctl_.get()->*fn)();
    } catch (const std::exception& e) {
      return std::string(what) + ": " + e.what();
    }
    return "";
  }

  // The abort and the final status under the controller lock: the worker cannot poll (and release the controller)
  // between the request and the abort, nor publish a status after it.
  std::string abort_run() {
    {
      std::lock_guard<std::mutex> lock(controller_mutex_);
      const std::string why = command_locked("abort", &control::Controller::abort);
      if (!why.empty()) return why;
      aborted_.store(true);
      std::lock_guard<std::mutex> status_lock(status_mutex_);
      status_.state = ProgramStatusMsg::ABORTED;
      status_.state_name = status_state_name(status_.state);
    }
    publish_status();
    ROS_WARN("gcode_bridge: program aborted");
    return "";
  }

  static bool reply(std_srvs::Trigger::Response& res, const std::string& why, const std::string& done) {
    res.success = why.empty();
    res.message = why.empty() ? done : why;
    return true;
  }

  bool on_start(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    ToolpathJobMsg::ConstPtr job;
    {
      std::lock_guard<std::mutex> lock(job_mutex_);
      job = last_job_;
    }
    if (!job) return reply(res, "no job received on the toolpath topic yet", "");
    const std::string why = start_run(*job, "", 1);
    return reply(res, why, "started " + status_copy().program);
  }
  bool on_pause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return reply(res, command("pause", &control::Controller::feed_hold), "feed hold");
  }
  bool on_resume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return reply(res, command("resume", &control::Controller::resume), "resumed");
  }
  bool on_abort(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return reply(res, abort_run(), "aborted");
  }

  // ------------------------------------------------------------------------------------------ the action

  void on_goal(const RunProgramGoalConstPtr& goal) {
    RunProgramResult result;
    ToolpathJobMsg job = goal->job;
    if (job.toolpaths.empty()) {
      std::lock_guard<std::mutex> lock(job_mutex_);
      if (last_job_) job = *last_job_;
    }
    const std::string why = start_run(job, goal->controller, goal->from_line);
    if (!why.empty()) {
      result.message = why;
      result.status = status_copy();
      action_.setAborted(result, why);
      return;
    }
    ::ros::WallRate rate(status_rate_);
    bool cancelled = false;
    while (running() && ::ros::ok()) {
      if (action_.isPreemptRequested() && !cancelled) {
        cancelled = true;
        const std::string abort_why = abort_run();
        if (!abort_why.empty()) ROS_ERROR("gcode_bridge: cancel: %s", abort_why.c_str());
      }
      RunProgramFeedback fb;
      fb.status = status_copy();
      action_.publishFeedback(fb);
      rate.sleep();
    }
    if (worker_.joinable() && !running()) {
      std::lock_guard<std::mutex> lock(start_mutex_);
      if (worker_.joinable()) worker_.join();
    }
    result.status = status_copy();
    result.program = result.status.program;
    result.lines = result.status.total_lines;
    result.acknowledged_line = result.status.acknowledged_line;
    result.duration = std::chrono::duration<double>(Clock::now() - started_).count();
    result.success = result.status.state == ProgramStatusMsg::DONE;
    result.message = result.success ? "program done" : result.status.state_name + (result.status.last_error.empty()
                                                                                      ? std::string()
                                                                                      : ": " + result.status.last_error);
    finish_goal(action_, result, cancelled, result.success);
  }

  std::string controller_, program_dir_;
  double status_rate_, stall_timeout_;
  bool verify_rs274_;
  gcode::PostOptions post_;
  control::ControllerOptions controller_options_;
  gcode::MachineLimits limits_;
  bool has_limits_ = false;
  int program_counter_ = 0;
  int idle_ticks_ = 0;

  std::mutex job_mutex_;
  ToolpathJobMsg::ConstPtr last_job_;

  std::mutex start_mutex_;       // one start at a time
  std::mutex controller_mutex_;  // the driver is not thread-safe: the worker and the commands take turns
  std::unique_ptr<control::Controller> ctl_;
  std::thread worker_;
  std::atomic<bool> stop_{false}, aborted_{false};
  Clock::time_point started_;

  std::mutex status_mutex_;
  ProgramStatusMsg status_;
  Eigen::Isometry3d machine_to_workpiece_ = Eigen::Isometry3d::Identity();
  geometry_msgs::Point anchor_;

  ::ros::Publisher status_pub_, marker_pub_;
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
