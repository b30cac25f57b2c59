// The one G-code reader (src/gcode) as its consumers use it: the interpreter line by line (what the controllers'
// resume and the limits checker follow), the simulator's program reader (verify) and the machine limits checker.
// A line is read or refused with its place; a move the reader makes goes to finite coordinates.
#include <vector>

#include "fuzz_support.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/verify/gcode_reader.hpp"

namespace {

using namespace rosmill;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return lines;
}

void require_finite_move(const core::CanonMove& m) {
  for (int a = 0; a < 3; ++a) {
    if (m.known_to & (1 << a)) fuzz::require(std::isfinite(m.to[a]), "a move to a coordinate that is not finite");
    if (m.known_from & (1 << a)) fuzz::require(std::isfinite(m.from[a]), "a move from a coordinate that is not finite");
  }
  if (m.is_arc()) fuzz::require(m.centre.allFinite(), "an arc centre that is not finite");
}

core::gcode::MachineLimits bundled_machine() {
  core::gcode::MachineLimits m;
  m.name = "fuzz";
  m.envelope.min = core::Vec3(-300, -200, -150);
  m.envelope.max = core::Vec3(300, 200, 100);
  m.table_z = -150;
  m.max_feed = 5000;
  m.max_spindle_rpm = 24000;
  m.clearance_over_stock = 2;
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = fuzz::text_of(data, size);
  const std::vector<std::string> lines = lines_of(text);
  fuzz::read_or_refuse([&] {
    core::gcode::Interpreter reader("fuzz.ngc");
    for (size_t i = 0; i < lines.size() && !reader.state().ended; ++i) {
      reader.read(lines[i], i + 1);
      if (reader.moved()) require_finite_move(reader.move());
    }
  });
  fuzz::read_or_refuse([&] {
    static const core::verify::ToolSetup tools = core::verify::tool_setup({"1=flat:6", "2=ball:3", "1"});
    const core::stock::MachineProgram program = core::verify::parse_gcode(text, "fuzz.ngc", tools);
    for (const core::CanonMove& m : program.moves) require_finite_move(m);
  });
  fuzz::read_or_refuse([&] {
    static const core::gcode::MachineLimits limits = bundled_machine();
    core::gcode::check_limits(lines, limits);
  });
  return 0;
}
