#include <cmath>

#include "rosmill/control/controller.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/gcode/number_format.hpp"

namespace rosmill::core::control {
namespace {

std::string num(double v) {
  std::string s;
  gcode::append_fixed(s, gcode::to_fixed(v, 4), 4);
  return s;
}

}  // namespace

std::vector<std::string> resume_preamble(const std::vector<std::string>& program, const SendOptions& o,
                                         const std::string& dialect) {
  if (o.from_line < 1 || o.from_line > program.size())
    throw Error("--from-line", "line " + std::to_string(o.from_line) + " is outside the program (1.." +
                                   std::to_string(program.size()) + ")");
  std::vector<std::string> pre;
  if (o.from_line == 1) return pre;
  // The modal state before the line, and the highest point the program reached before it: a height known to
  // clear the part (unless given).
  gcode::Interpreter reader;
  double highest = -INFINITY;
  std::vector<std::string> offsets;  // coordinate system data the skipped lines set (G10 L2): set it again
  for (size_t i = 0; i + 1 < o.from_line; ++i) {
    reader.read(program[i], i + 1);
    if (reader.block().has_g(100)) offsets.push_back(program[i]);
    if (reader.moved() && (reader.move().known_to & 4)) highest = std::max(highest, reader.move().to.z());
  }
  const gcode::ModalState& s = reader.state();
  if (s.feed_mode == 93) throw Error("--from-line", "a resume in inverse-time feed (G93) is not supported");
  const double safe = std::isnan(o.safe_z) ? highest : o.safe_z;
  const double unit = s.metric ? 1.0 : 1.0 / 25.4;  // positions are scanned in mm; write them in program units
  pre.push_back("(rosmill resume at line " + std::to_string(o.from_line) + ")");
  pre.insert(pre.end(), offsets.begin(), offsets.end());
  pre.push_back(std::string(s.metric ? "G21" : "G20") + " G" + std::to_string(s.plane) + " " +
                gcode::work_offset_code(s.work_offset) + " G90 G94");
  if (s.tool > 0) {
    if (dialect == "linuxcnc") {
      pre.push_back("T" + std::to_string(s.tool) + " M6");
    } else {
      pre.push_back("(tool T" + std::to_string(s.tool) + " must be in the spindle)");
    }
  }
  if (s.length_offset >= 0 && dialect == "linuxcnc") pre.push_back("G43 H" + std::to_string(s.length_offset));
  if (s.spindle == 3 || s.spindle == 4)
    pre.push_back("S" + num(s.spindle_rpm) + " M" + std::to_string(s.spindle));
  if (s.mist) pre.push_back("M7");
  if (s.flood) pre.push_back("M8");
  const bool all_known = s.known[0] && s.known[1] && s.known[2];
  if (all_known && std::isfinite(safe)) {
    const double z_up = std::max(safe, s.position.z());
    pre.push_back("G0 Z" + num(z_up * unit));
    pre.push_back("G0 X" + num(s.position.x() * unit) + " Y" + num(s.position.y() * unit));
    // Down into the cut at the feed (the material there may not be cut yet); not when already at the height.
    const double feed = s.feed > 0 ? s.feed : o.resume_feed;
    if (num(s.position.z()) != num(z_up)) pre.push_back("G1 Z" + num(s.position.z() * unit) + " F" + num(feed * unit));
    else if (s.feed > 0) pre.push_back("F" + num(s.feed * unit));
  } else {
    // Only Z known (the program's first retract, before any XY): that height again, as the program went there.
    if (s.known[2]) pre.push_back("G0 Z" + num(s.position.z() * unit));
    if (s.feed > 0) pre.push_back("F" + num(s.feed * unit));
  }
  if (!s.absolute) pre.push_back("G91");
  return pre;
}

std::vector<std::string> resumed_rest(const std::vector<std::string>& program, size_t from_line) {
  if (from_line < 1 || from_line > program.size())
    throw Error("--from-line", "line " + std::to_string(from_line) + " is outside the program (1.." +
                                   std::to_string(program.size()) + ")");
  std::vector<std::string> rest(program.begin() + static_cast<std::ptrdiff_t>(from_line - 1), program.end());
  if (from_line == 1) return rest;
  // The preamble's own moves leave the controller in G0 or G1: the first line that moves needs the program's
  // motion word again if it relies on the modal one (later lines then find the program's mode in force).
  gcode::Interpreter reader;
  for (size_t i = 0; i + 1 < from_line; ++i) reader.read(program[i], i + 1);
  const int motion = reader.state().motion;
  for (size_t i = 0; i < rest.size(); ++i) {
    const gcode::Block& b = reader.read(rest[i], from_line + i);
    if (!reader.moved()) continue;
    bool motion_word = false;
    for (int k = 0; k < b.g_count; ++k) motion_word |= b.g[k] == 0 || b.g[k] == 10 || b.g[k] == 20 || b.g[k] == 30;
    if (motion_word || motion < 0) break;
    // The motion word goes after the line number, if any (a line number comes first in a line).
    const std::string word = "G" + std::to_string(motion) + " ";
    std::string& line = rest[i];
    const size_t first = line.find_first_not_of(' ');
    const size_t at = b.has('N') ? line.find(' ', first) : first;
    line.insert(at == std::string::npos ? line.size() : (b.has('N') ? at + 1 : at), word);
    break;
  }
  return rest;
}

std::vector<std::string> resumed_program(const std::vector<std::string>& program, const SendOptions& o,
                                         const std::string& dialect) {
  std::vector<std::string> out = resume_preamble(program, o, dialect);
  const std::vector<std::string> rest = resumed_rest(program, o.from_line);
  out.insert(out.end(), rest.begin(), rest.end());
  return out;
}

}  // namespace rosmill::core::control
