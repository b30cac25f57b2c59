#include "rosmill/control/program_run.hpp"

#include "rosmill/error.hpp"

namespace rosmill::core::control {

RunVerdict RunMonitor::observe(ControllerStatus& s, Clock::time_point now) {
  if (s.state == RunState::Finished) return RunVerdict::Finished;
  if (s.state == RunState::Error || s.state == RunState::Alarm || s.state == RunState::Disconnected ||
      s.state == RunState::Idle) {
    // Idle or disconnected before the end: the controller dropped the program (a reset, a lost link).
    if (s.error.empty()) s.error = std::string("the controller went ") + run_state_name(s.state);
    return RunVerdict::Failed;
  }
  const bool moved = first_ || s.acknowledged_line != previous_.acknowledged_line ||
                     s.current_line != previous_.current_line ||
                     (s.position - previous_.position).norm() > 1e-6 || s.state != previous_.state;
  first_ = false;
  previous_ = s;
  if (moved || s.state == RunState::Paused) last_change_ = now;
  if (std::chrono::duration<double>(now - last_change_).count() > stall_s_) {
    s.error = "no progress for " + std::to_string(stall_s_) + " s at program line " + std::to_string(s.current_line);
    return RunVerdict::Failed;
  }
  return RunVerdict::Going;
}

ProgramRun::ProgramRun(std::unique_ptr<Controller> controller, const std::vector<std::string>& program,
                       const SendOptions& options, double stall_s, Listener on_status)
    : controller_(std::move(controller)), on_status_(std::move(on_status)) {
  controller_->connect();
  controller_->start(program, options);
  worker_ = std::thread(&ProgramRun::watch, this, stall_s);
}

ProgramRun::~ProgramRun() {
  if (active_.load()) {
    try {
      abort();
    } catch (const std::exception&) {
      // Best effort at shutdown: the connection is closed below either way.
    }
  }
  join();
  try {
    controller_->disconnect();
  } catch (const std::exception&) {
  }
}

void ProgramRun::watch(double stall_s) {
  RunMonitor monitor(stall_s);
  while (active_.load()) {
    RunVerdict verdict;
    {
      // aborted_ is set under this lock once the abort went out: no poll and no status after it.
      std::lock_guard<std::mutex> lock(controller_mutex_);
      if (aborted_.load()) break;
      ControllerStatus s = controller_->poll(0.02);
      verdict = monitor.observe(s);
      // The run is over before anyone hears that it is: a new run asked for on hearing it must not be refused.
      if (verdict != RunVerdict::Going) active_.store(false);
      if (on_status_) on_status_(s, verdict);
    }
    if (verdict != RunVerdict::Going) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  active_.store(false);
}

void ProgramRun::command(void (Controller::*fn)()) {
  std::lock_guard<std::mutex> lock(controller_mutex_);
  if (!active_.load()) throw Error(controller_->describe(), "no program is running");
  (controller_.get()->*fn)();
}

void ProgramRun::feed_hold() { command(&Controller::feed_hold); }
void ProgramRun::resume() { command(&Controller::resume); }

void ProgramRun::abort() {
  std::lock_guard<std::mutex> lock(controller_mutex_);
  if (!active_.load()) throw Error(controller_->describe(), "no program is running");
  controller_->abort();
  aborted_.store(true);
  active_.store(false);
}

void ProgramRun::join() {
  if (worker_.joinable() && worker_.get_id() != std::this_thread::get_id()) worker_.join();
}

ControllerStatus run_to_end(Controller& c, const std::vector<std::string>& program, const SendOptions& o,
                            const Progress& progress, double stall_s) {
  c.start(program, o);
  RunMonitor monitor(stall_s);
  for (;;) {
    ControllerStatus s = c.poll(0.05);
    if (progress) progress(s);
    const RunVerdict verdict = monitor.observe(s);
    if (verdict == RunVerdict::Finished) return s;
    if (verdict == RunVerdict::Failed)
      throw Error(c.describe(), s.error + "; resume with --from-line " + std::to_string(s.acknowledged_line + 1));
  }
}

}  // namespace rosmill::core::control
