// A program running on a controller, watched to its end: the one place that decides when a run is finished, has
// failed (the controller's error or alarm, a lost connection, a controller gone idle mid-program) or has stalled
// (no line and no axis moved for `stall_s` while running; a feed hold is not a stall). `rosmill send` runs a
// program in the calling thread (run_to_end); the ROS bridge runs it on a worker thread (ProgramRun) while its
// services hold, resume or abort it.
#pragma once
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "rosmill/control/controller.hpp"

namespace rosmill::core::control {

enum class RunVerdict { Going, Finished, Failed };

// Judges a run from the statuses polled one after another.
class RunMonitor {
 public:
  using Clock = std::chrono::steady_clock;
  explicit RunMonitor(double stall_s) : stall_s_(stall_s) {}
  // On Failed, `s.error` says why (the controller's own message when it gave one).
  RunVerdict observe(ControllerStatus& s, Clock::time_point now = Clock::now());

 private:
  double stall_s_;
  ControllerStatus previous_;
  Clock::time_point last_change_ = Clock::now();
  bool first_ = true;
};

// A program started on a controller and polled on a worker thread until it ends, fails, stalls or is aborted.
// `on_status` is called from the worker after every poll with the monitor's verdict, while the run holds the
// controller (it must not call back into the run); it is not called after
// abort() has returned. The controller is driven by one thread at a time (drivers are not thread-safe).
class ProgramRun {
 public:
  using Listener = std::function<void(const ControllerStatus&, RunVerdict)>;

  // Connects and starts the program (blocking while the controller connects); throws Error when it cannot.
  ProgramRun(std::unique_ptr<Controller> controller, const std::vector<std::string>& program,
             const SendOptions& options, double stall_s, Listener on_status);
  // Aborts a run still going (a sender that goes away mid-program would leave the machine half way).
  ~ProgramRun();
  ProgramRun(const ProgramRun&) = delete;
  ProgramRun& operator=(const ProgramRun&) = delete;

  // Feed hold, resume, abort on the running program; throw Error when the controller refuses.
  void feed_hold();
  void resume();
  void abort();
  bool active() const { return active_.load(); }
  // Waits for the worker to end (after the program's end, a failure or an abort).
  void join();

 private:
  void watch(double stall_s);
  void command(void (Controller::*fn)());

  std::unique_ptr<Controller> controller_;
  Listener on_status_;
  std::mutex controller_mutex_;
  std::atomic<bool> active_{true}, aborted_{false};
  std::thread worker_;
};

// Runs the program to its end in this thread, calling `progress` after each poll. Throws Error with the
// controller's message and the line to resume from on a failure or a stall.
using Progress = std::function<void(const ControllerStatus&)>;
ControllerStatus run_to_end(Controller& c, const std::vector<std::string>& program, const SendOptions& options,
                            const Progress& progress = {}, double stall_s = 60.0);

}  // namespace rosmill::core::control
