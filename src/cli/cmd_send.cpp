// rosmill send PROGRAM --controller linuxcnc://HOST:PORT | grbl:///dev/ttyX?baud=N | grbl+tcp://HOST:PORT | file:///DIR
//   [--from-line N] [--machine FILE | --no-limits] [--verify] [--program-dir DIR] [--dialect ..] [--timeout S]
// Checks the program against the machine's limits (and with --verify LinuxCNC's rs274) before anything is sent,
// then runs it on the controller with a progress bar on a terminal and plain progress lines otherwise. Ctrl-C
// stops the machine (abort) and says from which line to resume.
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "command.hpp"
#include "config_file.hpp"
#include "rosmill/control/controller.hpp"
#include "rosmill/control/program_run.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/prepare_program.hpp"

namespace rosmill::core::cli {
namespace {

struct SendArgs {
  std::string program, controller, machine, program_dir, dialect;
  size_t from_line = 1;
  bool no_limits = false, verify = false;
  double stock_top = NAN, timeout = 10.0, stall = 60.0;
};

std::atomic<bool> interrupted{false};
extern "C" void on_interrupt(int) { interrupted = true; }

// The dialect the controller speaks, from the URL's scheme unless given.
std::string dialect_for(const SendArgs& a) {
  if (!a.dialect.empty()) return gcode::find_dialect(a.dialect).name;
  return a.controller.rfind("grbl", 0) == 0 ? "grbl" : "linuxcnc";
}

// Progress: a bar redrawn in place on a terminal, a line per tenth of the program (and per state change) otherwise.
class ProgressReport {
 public:
  explicit ProgressReport(bool terminal) : terminal_(terminal) {}

  void operator()(const control::ControllerStatus& s) {
    const size_t total = std::max<size_t>(s.total_lines, 1);
    const int percent = static_cast<int>(100 * std::min(s.acknowledged_line, total) / total);
    if (terminal_) {
      constexpr int width = 30;
      const int filled = percent * width / 100;
      std::fprintf(stderr, "\r[%s%s] %3d%%  line %zu/%zu  %-9s", std::string(filled, '#').c_str(),
                   std::string(width - filled, '.').c_str(), percent, s.acknowledged_line, s.total_lines,
                   control::run_state_name(s.state));
      std::fflush(stderr);
      drawn_ = true;
    } else if (percent / 10 != last_tenth_ || s.state != last_state_) {
      std::printf("progress %d%% line %zu/%zu %s\n", percent, s.acknowledged_line, s.total_lines,
                  control::run_state_name(s.state));
      std::fflush(stdout);
    }
    last_tenth_ = percent / 10;
    last_state_ = s.state;
    if (interrupted) throw Error("send", "interrupted");
  }
  void end_line() {
    if (drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
  }

 private:
  bool terminal_;
  bool drawn_ = false;
  int last_tenth_ = -1;
  control::RunState last_state_ = control::RunState::Disconnected;
};

void run(const SendArgs& a) {
  const std::vector<std::string> lines = gcode::read_program_lines(a.program);
  // Safety before anything is sent: limits always (unless --no-limits), LinuxCNC's interpreter on request.
  gcode::ProgramChecks checks;
  checks.machine = machine_to_check(a.machine, a.no_limits);
  checks.limits.stock_top = a.stock_top;
  checks.rs274 = a.verify;
  gcode::check_program(lines, checks, a.program);
  if (a.from_line < 1 || a.from_line > lines.size())
    throw Error("--from-line", std::to_string(a.from_line) + " is outside the program (1.." +
                                   std::to_string(lines.size()) + ")");

  control::ControllerOptions co;
  co.dialect = dialect_for(a);
  co.program_dir = a.program_dir;
  co.program_name = std::filesystem::path(a.program).filename().string();
  co.reply_timeout_s = a.timeout;
  std::unique_ptr<control::Controller> c = control::open_controller(a.controller, co);
  c->connect();

  control::SendOptions so;
  so.from_line = a.from_line;
  ProgressReport progress(::isatty(STDERR_FILENO) == 1);
  interrupted = false;
  auto previous = std::signal(SIGINT, on_interrupt);
  control::ControllerStatus last;
  try {
    last = control::run_to_end(*c, lines, so, [&](const control::ControllerStatus& s) {
      last = s;
      progress(s);
    }, a.stall);
  } catch (const Error& e) {
    progress.end_line();
    std::signal(SIGINT, previous);
    if (!interrupted) throw;
    c->abort();  // Ctrl-C: stop the machine now
    throw Error(c->describe(), "interrupted and aborted; resume with --from-line " +
                                   std::to_string(last.acknowledged_line + 1));
  }
  progress.end_line();
  std::signal(SIGINT, previous);
  c->disconnect();
  std::printf("sent %s to %s: %zu lines, finished\n", a.program.c_str(), c->describe().c_str(), lines.size());
}

CommandRegistration reg([](CLI::App& app) {
  auto a = std::make_shared<SendArgs>();
  auto* cmd = app.add_subcommand("send", "run a G-code program on a controller (LinuxCNC, GRBL, or a folder)");
  cmd->add_option("PROGRAM", a->program, "the program (.ngc)")->required();
  cmd->add_option("--controller", a->controller,
                  "linuxcnc://HOST:PORT, grbl:///dev/ttyX?baud=115200, grbl+tcp://HOST:PORT or file:///DIR")
      ->required();
  cmd->add_option("--from-line", a->from_line, "resume at this program line (restores the modal state first)");
  cmd->add_option("--machine", a->machine,
                  "machine limits the program must keep (default config/machine.yaml here, else the package's)");
  cmd->add_flag("--no-limits", a->no_limits, "send without checking the machine's limits");
  cmd->add_option("--stock-top", a->stock_top, "stock top z for the rapid clearance check (default: highest cut)");
  cmd->add_flag("--verify", a->verify, "refuse a program LinuxCNC's interpreter (rs274) refuses, naming its line");
  cmd->add_option("--program-dir", a->program_dir, "LinuxCNC: absolute folder the controller reads programs from");
  cmd->add_option("--dialect", a->dialect, "linuxcnc or grbl (default: from the controller URL)");
  cmd->add_option("--timeout", a->timeout, "seconds to wait for a controller reply")->capture_default_str();
  cmd->add_option("--stall", a->stall, "seconds without progress before giving up")->capture_default_str();
  cmd->callback([a] { run(*a); });
});

}  // namespace
}  // namespace rosmill::core::cli
