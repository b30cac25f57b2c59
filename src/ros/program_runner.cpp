#include "rosmill/ros/program_runner.hpp"

#include <algorithm>

#include <ros/ros.h>
#include <sys/stat.h>

#include <filesystem>

#include "rosmill/error.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/program_status.hpp"

namespace rosmill::edge {
namespace {

void make_program_dir(const std::string& dir) {
  if (dir.empty() || dir.front() != '/')
    throw Error("parameter program_dir", "must be an absolute folder, got '" + dir + "'");
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir))
    throw Error("parameter program_dir", "cannot create the folder " + dir + ": " + ec.message());
  ::chmod(dir.c_str(), 0755);  // a controller running as another user reads the programs from here
}

}  // namespace

RunnerSettings runner_settings(const ::ros::NodeHandle& pnh) {
  RunnerSettings s;
  s.controller = string_param(pnh, "controller", "file:///tmp/rosmill");
  s.program_dir = string_param(pnh, "program_dir", "/tmp/rosmill");
  s.status_rate = double_param(pnh, "status_rate", 10.0, 5.0, 100.0);
  s.stall_timeout = double_param(pnh, "stall_timeout", 60.0, 1.0, 3600.0);
  s.post.dialect = string_param(pnh, "dialect", "linuxcnc");
  gcode::find_dialect(s.post.dialect);  // validates the name now
  s.post.arcs = bool_param(pnh, "arcs", false);
  // 0: from the toolpaths' tolerance (gcode::decimals_for_tolerance).
  s.post.decimals = int_param(pnh, "decimals", 0, 0, 6);
  s.checks.rs274 = bool_param(pnh, "verify_rs274", true);
  const std::string machine = string_param(pnh, "machine", "");
  if (!machine.empty())
    s.checks.machine = gcode::load_machine_limits(machine);
  else if (!bool_param(pnh, "no_limits", false))
    throw Error("parameter machine", "is required (the machine limits file, config/machine.yaml); set no_limits "
                                     "to true to run programs without checking the machine's limits");
  s.work_offset = work_offset_source(pnh);
  s.controller_options.reply_timeout_s = double_param(pnh, "reply_timeout", 10.0, 0.1, 600.0);
  s.controller_options.dialect = s.post.dialect;
  s.controller_options.program_dir = s.program_dir;
  control::open_controller(s.controller, s.controller_options);  // a malformed URI stops the node now
  make_program_dir(s.program_dir);
  return s;
}

ProgramRunner::ProgramRunner(RunnerSettings settings, ProgramStatusBoard& board, const tf2_ros::Buffer* tf)
    : settings_(std::move(settings)), board_(board), tf_(tf) {}

std::string ProgramRunner::write_program(const msg::ToolpathJob& msg, const Job& job, gcode::Program& program,
                                         std::optional<gcode::WorkOffset>& offset) {
  if (job.empty()) throw Error("job", "has no toolpath (none received on the toolpath topic yet?)");
  gcode::PostOptions options = settings_.post;
  options.title = "rosmill gcode_bridge: " + msg.toolpaths[0].strategy + ", setup " + msg.toolpaths[0].setup;
  // A job's setup brings its own work offset (its datum on the machine); else the workpiece frame's on tf.
  options.work_offset = offset = msg.work_offset ? work_offset_of(msg) : settings_.work_offset.now(tf_);
  if (!msg.setup_note.empty()) options.work_offset_note = msg.setup_note;
  const bool indexed = std::any_of(job.begin(), job.end(), [](const core::Toolpath& tp) { return tp.indexed; });
  if (indexed) {
    // A 3+2 job: the part turns between setups, so the tool must wait above it at the trunnion's safe Z.
    if (!settings_.checks.machine || !settings_.checks.machine->trunnion)
      throw Error("job", "is indexed for a trunnion table (3+2), but the bridge's machine file has no rotary axes: "
                         "set ~machine to one with `rotary:` (config/machine_xyzac.yaml)");
    options.index_safe_z = settings_.checks.machine->trunnion->safe_z;
  }
  const bool multi_axis = std::any_of(job.begin(), job.end(), [](const core::Toolpath& tp) { return tp.multi_axis(); });
  if (multi_axis) {
    // Simultaneous five- or four-axis: written for the trunnion's tool-centre-point control, which the machine file
    // must say it has (the post refuses the job otherwise).
    if (!settings_.checks.machine)
      throw Error("job",
                  "carries a tool axis at every move (five-axis), and the bridge has no machine file: set "
                  "~machine to a trunnion with tool-centre-point control (config/machine_xyzac_tcp.yaml)");
    options = gcode::with_tool_centre_point(options, *settings_.checks.machine, "~machine");
  }
  gcode::ProgramChecks checks = settings_.checks;
  checks.limits.rapids_checked_by_stock = msg.rapids_checked_by_stock;
  program = gcode::prepare_program(job, options, checks).program;
  const std::string path = settings_.program_dir + "/rosmill-" + std::to_string(::ros::WallTime::now().sec) + "-" +
                           std::to_string(++program_counter_) + ".ngc";
  gcode::write_program(path, program);
  ::chmod(path.c_str(), 0644);
  return path;
}

std::string ProgramRunner::start(const msg::ToolpathJob& job, const std::string& uri, uint32_t from_line) {
  std::lock_guard<std::mutex> lock(run_mutex_);
  if (run_ && run_->active()) return "a program is running on " + board_.copy().controller + ": abort it first";
  run_.reset();
  const std::string url = uri.empty() ? settings_.controller : uri;
  try {
    const Job core_job = from_job_msg(job);
    gcode::Program program;
    std::optional<gcode::WorkOffset> offset;
    const std::string path = write_program(job, core_job, program, offset);
    control::SendOptions send;
    send.from_line = std::max<uint32_t>(from_line, 1);
    if (send.from_line > program.lines.size())
      throw Error("from_line", std::to_string(send.from_line) + " is past the program's " +
                                   std::to_string(program.lines.size()) + " lines");
    auto controller = control::open_controller(url, settings_.controller_options);
    const gcode::MachineLimits* machine = settings_.checks.machine ? &*settings_.checks.machine : nullptr;
    const std::optional<gcode::WorkOffset> g54 = offset ? offset : machine ? std::optional(machine->work_offset)
                                                                             : std::nullopt;
    board_.begin(url, path, program.lines.size(),
                 program_placement(job, core_job, g54, machine ? machine->trunnion : std::nullopt));
    run_ = std::make_unique<control::ProgramRun>(
        std::move(controller), program.lines, send, settings_.stall_timeout,
        [this](const control::ControllerStatus& s, control::RunVerdict v) { board_.update(s, v); });
    ROS_INFO("gcode_bridge: %s: %zu lines on %s", path.c_str(), program.lines.size(), url.c_str());
  } catch (const std::exception& e) {
    board_.set_state(msg::ProgramStatus::ERROR, e.what());
    return e.what();
  }
  started_ = std::chrono::steady_clock::now();
  board_.started();
  return "";
}

std::string ProgramRunner::command(const char* what, void (control::ProgramRun::*fn)()) {
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

double ProgramRunner::seconds_running() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

RunProgramResult run_program_goal(const RunProgramGoal& goal, const msg::ToolpathJob& last_job, ProgramRunner& runner,
                                  ProgramStatusBoard& board, const ProgramGoalHooks& hooks, bool& cancelled) {
  RunProgramResult result;
  const msg::ToolpathJob& job = goal.job.toolpaths.empty() ? last_job : goal.job;
  const std::string why = runner.start(job, goal.controller, goal.from_line);
  if (!why.empty()) {
    result.message = why;
    // Not the board's status: that is the run before, which this goal did not start.
    result.status = refused_status(goal.controller.empty() ? runner.settings().controller : goal.controller, why);
    result.status.header.frame_id = board.copy().header.frame_id;
    return result;
  }
  ::ros::WallRate rate(runner.settings().status_rate);
  cancelled = false;
  while (board.running() && ::ros::ok()) {
    if (hooks.cancel_requested() && !cancelled) {
      cancelled = true;
      const std::string abort_why = runner.abort();
      if (!abort_why.empty()) ROS_ERROR("gcode_bridge: cancel: %s", abort_why.c_str());
    }
    RunProgramFeedback fb;
    fb.status = board.copy();
    hooks.feedback(fb);
    rate.sleep();
  }
  result.status = board.copy();
  result.program = result.status.program;
  result.lines = result.status.total_lines;
  result.acknowledged_line = result.status.acknowledged_line;
  result.duration = runner.seconds_running();
  result.success = result.status.state == msg::ProgramStatus::DONE;
  result.message = result.success ? "program done"
                                  : result.status.state_name +
                                        (result.status.last_error.empty() ? std::string() : ": " + result.status.last_error);
  return result;
}

}  // namespace rosmill::edge
