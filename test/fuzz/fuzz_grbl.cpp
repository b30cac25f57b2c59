// The GRBL driver reading what a board answers (ok, error:N, ALARM:N, status reports <...|MPos:x,y,z|...>, the
// greeting) while it streams a short program: any reply sequence leaves a consistent status or a reported lost
// connection, never a crash or a read past a reply.
#include "fuzz_support.hpp"
#include "fuzz_transport.hpp"
#include "rosmill/control/grbl.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rosmill;
  using core::control::RunState;
  static const std::vector<std::string> program = {"G21 G90 G17", "S1000 M3", "G0 Z5", "G1 Z-1 F300 (plunge)",
                                                   "X10 Y5",      "G0 Z5",    "M5",    "M30"};
  core::control::ControllerOptions options;
  options.rx_buffer = 24;  // a few lines in flight at once
  options.status_interval_s = 0;
  const std::string replies = fuzz::text_of(data, size);
  core::control::GrblController grbl([&] { return std::make_unique<fuzz::ScriptedPeer>(replies); }, "grbl fuzz",
                                     options, 0.0);
  fuzz::read_or_refuse([&] {
    grbl.connect();
    grbl.start(program, {});
    // The peer never keeps the driver waiting (each read gets bytes, or the end of the connection), so a poll
    // reads on until its time is up or the input ends, and the input's end (the peer closing) is reached.
    for (size_t polls = 0; polls <= size + 1; ++polls) {
      const core::control::ControllerStatus s = grbl.poll(0.05);
      fuzz::require(s.acknowledged_line <= s.total_lines, "acknowledged beyond the program's end");
      fuzz::require(s.state != RunState::Disconnected || !s.error.empty(), "a lost connection without a reason");
      if (s.state == RunState::Disconnected || s.state == RunState::Finished) break;
    }
  });
  return 0;
}
