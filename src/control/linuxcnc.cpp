#include "rosmill/control/linuxcnc.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <sstream>
#include <vector>
#include <thread>

#include "rosmill/error.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/text_words.hpp"

namespace rosmill::core::control {
namespace {

using Clock = std::chrono::steady_clock;

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// "part.ngc" -> "part"; empty -> "rosmill".
std::string file_stem(const std::string& name) {
  if (name.empty()) return "rosmill";
  const size_t dot = name.rfind('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

}  // namespace

LinuxcncController::LinuxcncController(std::string host, int port, const ControllerOptions& o,
                                       std::function<std::unique_ptr<Transport>()> open)
    : host_(std::move(host)), port_(port), open_(std::move(open)), opt_(o) {}

std::string LinuxcncController::describe() const { return "linuxcnc://" + host_ + ":" + std::to_string(port_); }

std::string LinuxcncController::reply_for(const std::string& request, const std::string& key) {
  if (!transport_) throw Error(describe(), "not connected");
  transport_->write(request + "\r\n");
  const auto start = Clock::now();
  std::string line;
  for (;;) {
    const double left = opt_.reply_timeout_s - std::chrono::duration<double>(Clock::now() - start).count();
    if (left <= 0 || !reader_->next(line, left))
      throw Error(describe(), "no reply to '" + request + "' within " + std::to_string(opt_.reply_timeout_s) + " s");
    if (line.empty() || line == request) continue;  // blank separators and echoes
    if (line.rfind(key, 0) == 0) return line.substr(std::min(line.size(), key.size() + 1));
    if (line.find("NAK") != std::string::npos)
      throw Error(describe(), "linuxcncrsh refused '" + request + "': " + line);
  }
}

void LinuxcncController::set(const std::string& what) {
  const std::string reply = reply_for("set " + what, "SET " + upper(first_word(what)));
  if (reply != "ACK") throw Error(describe(), "linuxcncrsh refused 'set " + what + "': " + reply);
}

std::string LinuxcncController::get(const std::string& what) { return reply_for("get " + what, upper(first_word(what))); }

void LinuxcncController::connect() {
  transport_ = open_ ? open_() : open_tcp(host_, port_);
  reader_ = std::make_unique<LineReader>(*transport_);
  const std::string hello = reply_for("hello EMC rosmill 1.0", "HELLO");
  if (hello.rfind("ACK", 0) != 0) throw Error(describe(), "handshake refused: HELLO " + hello);
  transport_->write("set echo off\r\n");
  set("verbose on");  // from here every set is answered ACK or NAK
  set("enable EMCTOO");
  // "received", not "done": with "done" linuxcncrsh answers "set run" only when the program has ended (no status
  // meanwhile), and "set pause" on an idle interpreter never. The few commands that must have taken effect
  // before the next one are followed by an explicit "wait done", bounded by the timeout.
  set("set_wait received");
  set("timeout " + std::to_string(std::max(1.0, opt_.reply_timeout_s - 1.0)));  // "set_timeout" in older releases
  set("estop off");
  set("wait done");
  set("machine on");
  set("wait done");
  if (!opt_.home_if_needed) return;
  auto homed = [&] {
    std::istringstream in(get("joint_homed"));
    std::string w;
    for (int j = 0; j < 3 && in >> w; ++j)  // the reply lists unused joints too; X, Y and Z are the first three
      if (upper(w) != "YES") return false;
    return true;
  };
  if (homed()) return;
  set("mode manual");
  set("home -1");
  const auto start = Clock::now();
  while (!homed()) {
    if (std::chrono::duration<double>(Clock::now() - start).count() > 60)
      throw Error(describe(), "homing did not finish within 60 s");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

void LinuxcncController::start(const std::vector<std::string>& program, const SendOptions& o) {
  if (opt_.program_dir.empty() || opt_.program_dir.front() != '/')
    throw Error(describe(), "needs an absolute program folder the controller reads (--program-dir)");
  const std::vector<std::string> sent = resumed_program(program, o, opt_.dialect.empty() ? "linuxcnc" : opt_.dialect);
  // A new file per start: LinuxCNC may still hold the previous one open.
  const std::string path = opt_.program_dir + "/" + file_stem(opt_.program_name) + "-" + std::to_string(::getpid()) +
                           "-" + std::to_string(++file_counter_) + ".ngc";
  gcode::write_program_lines(path, sent);
  ::chmod(path.c_str(), 0644);  // the controller may run as another user
  preamble_lines_ = sent.size() - (program.size() - o.from_line + 1);
  from_line_ = o.from_line;
  status_ = ControllerStatus{};
  status_.total_lines = program.size();
  status_.acknowledged_line = o.from_line - 1;
  // "get error" hands out the last error once: read what an earlier program left, so that it is not taken for
  // this program's.
  get("error");
  set("mode auto");
  set("wait done");
  set("open " + path);
  set("wait done");
  const std::string err = get("error");
  if (upper(err) != "OK") throw Error(describe(), "cannot open " + path + ": " + err);
  set("run");
  status_.state = RunState::Running;
  seen_running_ = false;
}

size_t LinuxcncController::program_line_of(size_t file_line) const {
  if (file_line <= preamble_lines_) return 0;
  return file_line - preamble_lines_ - 1 + from_line_;
}

void LinuxcncController::lost(const Error& e) {
  transport_.reset();
  reader_.reset();
  status_.state = RunState::Disconnected;
  status_.error = std::string(e.what()) + " (program line " + std::to_string(status_.acknowledged_line) + " done)";
}

ControllerStatus LinuxcncController::poll(double timeout_s) {
  const auto start = Clock::now();
  if (!transport_) {
    status_.state = RunState::Disconnected;
    return status_;
  }
  try {
    const std::string run = upper(get("program_status"));
    const size_t line = program_line_of(std::strtoul(get("program_line").c_str(), nullptr, 10));
    std::istringstream pos(get("abs_act_pos"));
    // X Y Z A B C (and U V W): every axis of the machine's kinematics, whether or not it has a joint.
    std::vector<double> axes;
    for (double v; axes.size() < 9 && pos >> v;) axes.push_back(v);
    status_.position_known = axes.size() >= 3;
    if (status_.position_known) status_.position = Vec3(axes[0], axes[1], axes[2]);
    status_.rotary_known = axes.size() >= 6;
    if (status_.rotary_known) status_.a = axes[3], status_.c = axes[5];
    const std::string err = get("error");
    // A line outside the program (a stale or garbled reply) says nothing about it: it must not move the
    // acknowledged line past the program's end, where a resume would start.
    if (line > 0 && line <= status_.total_lines) {
      status_.current_line = line;
      status_.acknowledged_line = std::max(status_.acknowledged_line, line - 1);
    }
    if (upper(err) != "OK") {
      status_.state = RunState::Error;
      status_.error = "LinuxCNC: " + err + " (at program line " + std::to_string(status_.current_line) + ")";
    } else if (status_.state == RunState::Running || status_.state == RunState::Paused) {
      if (run == "RUNNING") {
        seen_running_ = true;
        status_.state = RunState::Running;
      } else if (run == "PAUSED") {
        seen_running_ = true;
        status_.state = RunState::Paused;
      } else if (run == "IDLE" && (seen_running_ || status_.current_line > 0)) {
        // Idle after the program was seen running, or after its lines were read: finished. Idle before either is
        // a start not yet taken up (a loaded machine takes seconds): still running, never finished by the clock,
        // or a program that never ran would be reported done.
        status_.state = RunState::Finished;
        status_.acknowledged_line = status_.total_lines;
      }
    }
  } catch (const Error& e) {
    lost(e);
    return status_;
  }
  const double left = timeout_s - std::chrono::duration<double>(Clock::now() - start).count();
  if (left > 0) std::this_thread::sleep_for(std::chrono::duration<double>(left));
  return status_;
}

void LinuxcncController::feed_hold() {
  set("pause");
  if (status_.state == RunState::Running) status_.state = RunState::Paused;
}

void LinuxcncController::resume() {
  set("resume");
  if (status_.state == RunState::Paused) status_.state = RunState::Running;
}

void LinuxcncController::abort() {
  set("abort");
  status_.state = RunState::Idle;
}

void LinuxcncController::disconnect() {
  if (transport_) {
    try {
      transport_->write("quit\r\n");
    } catch (const Error&) {
    }
  }
  transport_.reset();
  reader_.reset();
  status_.state = RunState::Disconnected;
}

}  // namespace rosmill::core::control
