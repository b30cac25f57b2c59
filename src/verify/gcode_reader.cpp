#include "rosmill/verify/gcode_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string_view>

#include "rosmill/error.hpp"
#include "rosmill/input_file.hpp"
#include "rosmill/gcode/interpreter.hpp"

namespace rosmill::core::verify {
namespace {

using gcode::Block;

// Why a letter other than the ones the verifier knows (F G H I J K M N P R S T X Y Z) is refused.
std::string refused_letter(char letter) {
  const std::string l(1, letter);
  if (letter == 'A' || letter == 'B' || letter == 'C' || letter == 'U' || letter == 'V' || letter == 'W')
    return "axis " + l + " is not supported (the verifier simulates 3-axis X Y Z programs)";
  if (letter == 'D') return "D (cutter radius compensation) is not supported";
  return "word " + l + " is not supported by the verifier";
}

// The G codes the simulation follows or that do not move the tool: motion G0-G3 and G80, the XY plane, units,
// distance modes, dwell, comp off, tool length (positions are tool tips), G54..G59 (a program's coordinates are
// the part's, whichever system holds them), path control, feed and spindle modes, canned-cycle return. Anything
// else would change the motion in a way the simulation does not model.
bool simulated_g(int g) {
  switch (g) {
    case 0: case 10: case 20: case 30: case 800: case 170: case 200: case 210: case 900: case 910: case 901: case 911:
    case 40: case 400: case 490: case 430: case 540: case 550: case 560: case 570: case 580: case 590:
    case 610: case 611: case 640: case 930: case 940: case 950:
    case 960: case 970: case 980: case 990:
      return true;
    default:
      return false;
  }
}

// Why an M code the simulation does not know is refused.
[[noreturn]] void refuse_m(int m, const gcode::Place& place) {
  const std::string where = place.str();
  if (m == 98 || m == 99) throw Error(where, "M" + std::to_string(m) + " (subroutines) is not supported");
  if (m >= 70 && m <= 73)
    throw Error(where, "M" + std::to_string(m) + " (saved modal state) is not supported by the verifier");
  throw Error(where, "M" + std::to_string(m) + " is not known to the verifier");
}

// M codes that do not move the tool or that the simulation follows (M2, M30, M6).
bool simulated_m(int m) {
  return (m >= 0 && m <= 9) || m == 30 || m == 60 || (m >= 48 && m <= 53) || (m >= 62 && m <= 68) ||
         (m >= 100 && m <= 199);
}

// M428 and M429: LinuxCNC's xyzac-trt switches to tool-centre-point kinematics and back (its configuration's
// remaps); the reader follows which one holds.
bool switches_kinematics(int m) { return m == 428 || m == 429; }

constexpr uint32_t letters(std::string_view s) {
  uint32_t bits = 0;
  for (char c : s) bits |= 1u << (c - 'A');
  return bits;
}

// The retract before a trunnion turns the part: G53 with G0 and linear axes alone (the position it leaves is
// unknown to the reader, which is what the simulation needs: no sweep from or to it).
bool rotary_retract(const Block& b, bool rotary) {
  return rotary && b.has_g(530) && b.has_g(0) && !(b.present & letters("ABCIJKR")) && b.has_linear();
}

// What the simulation cannot follow is refused before the block runs, naming the line.
void refuse_unsimulated(const Block& b, const gcode::Place& where, bool rotary) {
  if (b.block_delete) throw Error(where.str(), "block delete '/' is not supported");
  const uint32_t kKnown = letters("FGHIJKMNPRSTXYZ") | (rotary ? letters("AC") : 0u);
  const bool retract = rotary_retract(b, rotary);
  // G10 L2 P1..P6 sets the origin of G54..G59 on the machine (where the part was found, a setup's datum): the
  // program's coordinates, which the simulation follows in the part's frame, stay what they are. Other coordinate
  // system data is refused.
  const long p = b.has('P') ? std::lround(b.get('P')) : -1;
  const bool g54_data = b.has_g(100) && b.has('L') && std::lround(b.get('L')) == 2 && p >= 0 && p <= 6;
  if (b.has_g(100) && !g54_data)
    throw Error(where.str(), "G10 other than L2 P1..P6 (G54..G59's origin) is not supported by the verifier");
  if (const uint32_t other = b.present & ~kKnown & ~(g54_data ? 1u << ('L' - 'A') : 0u))
    for (int k = 0; k < 26; ++k)
      if (other >> k & 1u) throw Error(where.str(), refused_letter(static_cast<char>('A' + k)));
  for (int k = 0; k < b.g_count; ++k)
    if (!simulated_g(b.g[k]) && !(g54_data && b.g[k] == 100) && !(retract && b.g[k] == 530))
      throw Error(where.str(),
                  gcode::g_name(b.g[k]) + " is not supported by the verifier (it would change the motion)");
  for (int k = 0; k < b.m_count; ++k)
    if (!simulated_m(b.m[k]) && !(rotary && switches_kinematics(b.m[k]))) refuse_m(b.m[k], where);
}

// The one reader's canonical moves, with the tools of the setup, into the simulator's program.
class Reader {
 public:
  Reader(const std::string& name, const ToolSetup& tools, size_t expected_moves)
      : tools_(tools), reader_(name) {
    program_.moves.reserve(std::min(expected_moves, kMaxProgramMoves));
    if (tools.loaded) {
      program_.tools.push_back(*tools.loaded);
      current_ = 0;
    } else if (tools.tools.size() == 1) {
      current_ = tool_index(tools.tools.begin()->first, name);
    } else if (tools.tools.empty()) {
      throw Error(name, "no tool given for the G-code program (pass --tool, e.g. ball:6, or a tool table)");
    }
  }

  // Reads one line; false once the program has ended (M2, M30 or a closing '%').
  bool line(std::string_view raw, uint32_t number) {
    const Block& b = reader_.lex(raw, number);
    if (!b.percent && !b.empty()) {
      refuse_unsimulated(b, reader_.place(), tools_.rotary);
      tool_words(b);
    }
    reader_.execute();
    if (tools_.rotary && b.has_m(428)) tool_centre_point_ = true;
    if (tools_.rotary && b.has_m(429)) tool_centre_point_ = false;
    if (b.has_m(6)) current_ = tool_index(reader_.state().tool, reader_.where());
    if (reader_.moved()) add(reader_.move());
    return !reader_.state().ended;
  }

  stock::MachineProgram finish() {
    program_.from_gcode = true;
    return std::move(program_);
  }

 private:
  void tool_words(const Block& b) {
    if (b.has('T')) {
      const double t = b.get('T');
      const long n = std::lround(t);
      if (t != n || n < 0) throw Error(reader_.where(), "bad tool number T" + std::to_string(t));
      if (!tools_.tools.count(static_cast<int>(n)))
        throw Error(reader_.where(), not_in_table(n));
    }
    if (b.has_m(6) && !b.has('T') && reader_.state().selected_tool < 0)
      throw Error(reader_.where(), "M6 without a T word before it");
  }

  static std::string not_in_table(long n) {
    const std::string t = std::to_string(n);
    if (n == 0) return "tool T0 empties LinuxCNC's spindle: no tool is there to cut with";
    return "tool T" + t + " is not in the tool table: give it as --tool CUTTER@" + t + " (or " + t +
           "=CUTTER, e.g. flat:10@" + t + ") or in the table (--tools)";
  }

  int tool_index(int number, const std::string& where) {
    auto it = tools_.tools.find(number);
    if (it == tools_.tools.end()) throw Error(where, not_in_table(number));
    for (size_t i = 0; i < program_.tools.size(); ++i)
      if (program_.tools[i].id == number && (i > 0 || !tools_.loaded)) return static_cast<int>(i);
    Tool t = it->second;
    t.id = number;
    program_.tools.push_back(t);
    return static_cast<int>(program_.tools.size() - 1);
  }

  // A move is swept once all three axes are known, the first one from its own target.
  void add(const CanonMove& move) {
    if (move.is_arc() && move.turns != 1) throw Error(reader_.where(), "arcs of several turns (P) are not supported");
    if (!move.to_known()) return;  // still somewhere unknown: nothing to sweep yet
    if (current_ < 0)
      throw Error(reader_.where(), "a move before any tool change (T.. M6) and no tool given for the one in the "
                                   "spindle at the start (--tool)");
    // A zero-length line leaves the cutter where it is.
    if (move.from_known() && !move.is_arc() && (move.to - move.from).squaredNorm() == 0.0) return;
    if (program_.moves.size() >= kMaxProgramMoves)
      throw Error(reader_.where(), "the program has more than " + std::to_string(kMaxProgramMoves) +
                                       " moves, more than the verifier holds: verify it in parts");
    CanonMove& m = program_.moves.emplace_back(move);
    m.tool_centre_point = tool_centre_point_;
    if (!m.from_known()) {  // the first swept move starts at its own target
      m.from = m.to;
      m.known_from = m.known_to;
    }
    m.tool = static_cast<uint16_t>(current_);
  }

  const ToolSetup& tools_;
  gcode::Interpreter reader_;
  stock::MachineProgram program_;
  int current_ = -1;
  bool tool_centre_point_ = false;  // after M428, until M429
};

}  // namespace

stock::MachineProgram parse_gcode(const std::string& text, const std::string& name, const ToolSetup& tools) {
  Reader reader(name, tools, static_cast<size_t>(std::count(text.begin(), text.end(), '\n')));
  std::string_view rest(text);
  uint32_t number = 0;
  while (!rest.empty()) {
    const size_t eol = rest.find('\n');
    if (!reader.line(rest.substr(0, eol), ++number) || eol == std::string_view::npos) break;
    rest.remove_prefix(eol + 1);
  }
  return reader.finish();
}

stock::MachineProgram read_gcode(const std::string& path, const ToolSetup& tools) {
  return parse_gcode(read_input_file(path), path, tools);
}

ToolSetup tool_setup(const std::vector<std::string>& specs, const ToolTable* table) {
  ToolSetup setup;
  if (table)
    for (const Tool& t : table->tools) setup.tools[t.id] = t;
  std::vector<int> defined;
  int loaded_number = -1;
  std::string loaded_spec;
  for (const std::string& given : specs) {
    const std::string where = "--tool " + given;
    // "CUTTER@N", as `rosmill plan --tool` takes an inline tool, is "N=CUTTER".
    const size_t at = given.find('@');
    const std::string spec = given.find('=') == std::string::npos && at != std::string::npos
                                 ? std::to_string(parse_tool_number(given.substr(at + 1), where)) + "=" +
                                       given.substr(0, at)
                                 : given;
    const size_t eq = spec.find('=');
    std::string key = eq == std::string::npos ? spec : spec.substr(0, eq);
    if (!key.empty() && (key[0] == 'T' || key[0] == 't')) key = key.substr(1);
    const bool numbered = !key.empty() && key.find_first_not_of("0123456789") == std::string::npos && key.size() < 9;
    if (eq != std::string::npos && !numbered) throw Error(where, "bad tool number '" + key + "'");
    if (eq == std::string::npos && !loaded_spec.empty())
      throw Error(where, "two tools for the spindle at the start ('" + loaded_spec + "' and '" + spec + "')");
    if (eq == std::string::npos && numbered) {  // "N": tool N is loaded at the start
      loaded_number = std::stoi(key);
      loaded_spec = spec;
      continue;
    }
    Tool t = default_tool(parse_cutter_spec(eq == std::string::npos ? spec : spec.substr(eq + 1), where));
    t.name = spec;
    if (eq == std::string::npos) {
      setup.loaded = t;
      loaded_spec = spec;
      continue;
    }
    t.id = std::stoi(key);
    for (int d : defined)
      if (d == t.id) throw Error(where, "tool T" + std::to_string(t.id) + " given twice");
    defined.push_back(t.id);
    setup.tools[t.id] = t;
  }
  if (loaded_number >= 0) {
    auto it = setup.tools.find(loaded_number);
    if (it == setup.tools.end())
      throw Error("--tool " + loaded_spec, "tool T" + std::to_string(loaded_number) + " is not in the tool table");
    setup.loaded = it->second;
  }
  return setup;
}

}  // namespace rosmill::core::verify
