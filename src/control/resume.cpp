#include <cmath>

#include "rosmill/control/controller.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/block.hpp"
#include "rosmill/gcode/number_format.hpp"

namespace rosmill::control {
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
  const gcode::ModalState s = gcode::state_before(program, o.from_line - 1);
  // The highest point the program reached before: a height known to clear the part (unless given).
  double safe = o.safe_z;
  if (std::isnan(safe)) {
    gcode::ModalState scan;
    safe = -INFINITY;
    for (size_t i = 0; i + 1 < o.from_line; ++i) {
      const std::string where = "line " + std::to_string(i + 1);
      const auto bm = gcode::apply_block(scan, gcode::parse_block(program[i], where), where);
      if (bm.moved && bm.to_known[2]) safe = std::max(safe, bm.to.z());
    }
  }
  const double unit = s.metric ? 1.0 : 1.0 / 25.4;  // positions are scanned in mm; write them in program units
  pre.push_back("(rosmill resume at line " + std::to_string(o.from_line) + ")");
  pre.push_back(std::string(s.metric ? "G21" : "G20") + " G" + std::to_string(s.plane) + " G" +
                std::to_string(s.work_offset) + " G90 G94");
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
    const double feed = s.feed > 0 ? s.feed : o.resume_feed;
    pre.push_back("G1 Z" + num(s.position.z() * unit) + " F" + num(feed * unit));
    if (feed != s.feed && s.feed > 0) pre.push_back("F" + num(s.feed * unit));
  } else if (s.feed > 0) {
    pre.push_back("F" + num(s.feed * unit));
  }
  if (!s.absolute) pre.push_back("G91");
  return pre;
}

std::string resume_first_line(const std::vector<std::string>& program, size_t from_line) {
  const std::string& line = program.at(from_line - 1);
  if (from_line == 1) return line;
  const gcode::ModalState s = gcode::state_before(program, from_line - 1);
  const gcode::Block b = gcode::parse_block(line, "line " + std::to_string(from_line));
  bool motion_word = false;
  for (int g : b.g_codes()) motion_word |= g == 0 || g == 10 || g == 20 || g == 30;
  const bool axes = b.has('X') || b.has('Y') || b.has('Z');
  if (!axes || motion_word || s.motion < 0) return line;
  // After the preamble the controller's motion mode is G1: the line needs its own motion word again.
  std::string out = "G" + std::to_string(s.motion) + " ";
  if (b.has('N')) {
    // Keep the line number first.
    const size_t space = line.find(' ');
    return line.substr(0, space + 1) + out + line.substr(space + 1);
  }
  return out + line;
}

std::vector<std::string> resumed_program(const std::vector<std::string>& program, const SendOptions& o,
                                         const std::string& dialect) {
  std::vector<std::string> out = resume_preamble(program, o, dialect);
  out.push_back(resume_first_line(program, o.from_line));
  out.insert(out.end(), program.begin() + static_cast<std::ptrdiff_t>(o.from_line), program.end());
  return out;
}

}  // namespace rosmill::control
