// The LinuxCNC driver reading linuxcncrsh's replies (HELLO ACK, SET <what> ACK|NAK, PROGRAM_STATUS, PROGRAM_LINE,
// ABS_ACT_POS, ERROR) through the handshake, the start of a program and the status polls: any reply sequence
// leaves a consistent status or a reported fault, never a crash.
#include <cstdlib>
#include <filesystem>

#include "fuzz_support.hpp"
#include "fuzz_transport.hpp"
#include "rosmill/control/linuxcnc.hpp"

namespace {

// The folder the driver writes its program into (the controller would read it there): one for the run, removed
// at its end.
struct ProgramDir {
  std::string path;
  ProgramDir() {
    char name[] = "/tmp/rosmill-fuzz-linuxcnc-XXXXXX";
    if (!mkdtemp(name)) rosmill::fuzz::finding("cannot make a program folder");
    path = name;
  }
  ~ProgramDir() { std::filesystem::remove_all(path); }
};

const std::string& program_dir() {
  static const ProgramDir dir;
  return dir.path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rosmill;
  using core::control::RunState;
  static const std::vector<std::string> program = {"G21 G90", "G0 Z5", "G1 Z-1 F300", "X10", "G0 Z5", "M2"};
  core::control::ControllerOptions options;
  options.program_dir = program_dir();
  options.home_if_needed = false;  // homing waits 0.1 s between questions: the same replies, read the same way
  options.reply_timeout_s = 2;
  const std::string replies = fuzz::text_of(data, size);
  core::control::LinuxcncController cnc("fuzz", 5007, options,
                                        [&] { return std::make_unique<fuzz::ScriptedPeer>(replies); });
  fuzz::read_or_refuse([&] {
    cnc.connect();
    cnc.start(program, {});
    for (size_t polls = 0; polls <= size + 1; ++polls) {
      const core::control::ControllerStatus s = cnc.poll(0.0);
      fuzz::require(s.acknowledged_line <= s.total_lines, "acknowledged beyond the program's end");
      fuzz::require(s.current_line <= s.total_lines, "a current line beyond the program's end");
      if (s.state == RunState::Disconnected || s.state == RunState::Finished || s.state == RunState::Error) break;
    }
  });
  return 0;
}
