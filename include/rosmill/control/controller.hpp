// Controller drivers behind one interface: LinuxCNC (linuxcncrsh over TCP), GRBL (serial or TCP, character-
// counting streaming) and a folder a controller loads programs from.
//
// A driver knows the last program line the controller acknowledged (GRBL: its "ok"; LinuxCNC: the lines before
// the one it executes). After a fault — connection lost, controller error, alarm, timeout — a new start() with
// `from_line` = acknowledged + 1 resumes: the driver first restores the modal state the program had there
// (units, distance mode, plane, work offset, tool, spindle, coolant, feed, motion) and moves to where that line
// starts (up at the safe height, across, down at the feed), so nothing is lost and nothing is sent twice.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::control {

enum class RunState { Disconnected, Idle, Running, Paused, Alarm, Error, Finished };
const char* run_state_name(RunState s);

struct ControllerStatus {
  RunState state = RunState::Disconnected;
  size_t total_lines = 0;         // of the program
  size_t current_line = 0;        // 1-based program line being executed (0: unknown or not in the program)
  size_t acknowledged_line = 0;   // every program line up to this one was accepted by the controller
  Vec3 position = Vec3::Zero();   // machine position (mm)
  bool position_known = false;
  // A trunnion's rotary axes A and C (degrees), when the controller reports them (LinuxCNC's XYZAC machines).
  double a = 0, c = 0;
  bool rotary_known = false;
  std::string error;              // the controller's error or alarm, with the program line when known
};

struct SendOptions {
  size_t from_line = 1;     // 1-based; > 1 resumes (see above)
  double safe_z = NAN;      // resume: height of the move to the resume point (default: highest z before it)
  double resume_feed = 100; // resume: feed down to the resume point when the program had none yet (mm/min)
};

struct ControllerOptions {
  double reply_timeout_s = 10.0;    // a request without reply within this is a fault
  double status_interval_s = 0.2;   // GRBL: '?' polling period
  std::string program_dir;          // LinuxCNC: folder (readable by the controller) where programs are written
  std::string dialect;              // for resume preambles; empty: the driver's own
  size_t rx_buffer = 128;           // GRBL receive buffer (bytes)
  bool home_if_needed = true;       // LinuxCNC: home all joints when not homed
  std::string program_name;         // file name where programs are written (file://, LinuxCNC); default rosmill.ngc
};

class Controller {
 public:
  virtual ~Controller() = default;
  virtual std::string describe() const = 0;
  virtual void connect() = 0;
  // Starts (or resumes) a program; returns at once. poll() carries the work on.
  virtual void start(const std::vector<std::string>& program, const SendOptions& options) = 0;
  // Streams, reads replies and status for at most `timeout_s`; returns the status.
  virtual ControllerStatus poll(double timeout_s) = 0;
  virtual void feed_hold() = 0;
  virtual void resume() = 0;
  virtual void abort() = 0;
  // Clears an alarm (GRBL $X). Only on an explicit request: an alarm means the machine position may be lost.
  virtual void unlock() {}
  virtual void disconnect() = 0;
};

// linuxcnc://HOST:PORT, grbl:///dev/ttyX?baud=115200, grbl+tcp://HOST:PORT, file:///DIR. Throws Error naming
// the URL when it is malformed. connect() is left to the caller.
std::unique_ptr<Controller> open_controller(const std::string& url, const ControllerOptions& options = {});

// The lines a resume sends before program line `from_line` (1-based): the modal state scanned from the lines
// before it, then the way to where the line starts. `dialect` is "linuxcnc" or "grbl" (tool change words).
std::vector<std::string> resume_preamble(const std::vector<std::string>& program, const SendOptions& options,
                                         const std::string& dialect);
// Program lines from `from_line` on as they must be sent after the preamble: the first line that moves gets the
// program's modal motion word (G0..G3) back when it relies on it.
std::vector<std::string> resumed_rest(const std::vector<std::string>& program, size_t from_line);
// What a controller receives to run `program` from options.from_line: the preamble, the first line, the rest.
std::vector<std::string> resumed_program(const std::vector<std::string>& program, const SendOptions& options,
                                         const std::string& dialect);

}  // namespace rosmill::core::control
