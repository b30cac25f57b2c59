#include "rosmill/verify/gcode_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>

#include "rosmill/error.hpp"

namespace rosmill::verify {
namespace {

// Where a line is, spelled out only for an error message ("file:line").
struct Place {
  const std::string& name;
  uint32_t line = 0;
  std::string str() const { return name + ":" + std::to_string(line); }
};

// One block (line) of words after comments and spaces are removed.
struct Block {
  static constexpr int kMaxCodes = 8;
  int g[kMaxCodes], m[kMaxCodes];  // G numbers times ten (G90.1 -> 901); M numbers
  int ng = 0, nm = 0;
  double value[26] = {};           // the other words, by letter
  uint32_t has = 0;                // bit per letter
  bool has_word(char c) const { return has >> (c - 'A') & 1u; }
  double word(char c) const { return value[c - 'A']; }
  bool has_axis() const { return has_word('X') || has_word('Y') || has_word('Z'); }
};

// Comments out, spaces out, letters up: RS274 ignores spaces anywhere, even inside numbers ("X 1 0" is X10).
void strip_comments(std::string_view raw, std::string& out, const Place& where) {
  out.clear();
  bool in_paren = false;
  for (char c : raw) {
    if (in_paren) {
      if (c == ')') in_paren = false;
      continue;
    }
    if (c == '(') { in_paren = true; continue; }
    if (c == ';') break;
    if (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f') continue;
    out.push_back(c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c);
  }
  if (in_paren) throw Error(where.str(), "comment not closed with ')'");
}

// An RS274 number: optional sign, digits, optional point and digits (no exponent: "G0X5" is G0 X5).
double parse_number(std::string_view text, size_t& i, const Place& where, char letter) {
  bool negative = false;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
  const size_t start = i;
  size_t digits = 0;
  while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i, ++digits;
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i, ++digits;
  }
  if (digits == 0) throw Error(where.str(), std::string("word ") + letter + " has no number");
  double v = 0;
  std::from_chars(text.data() + start, text.data() + i, v);
  return negative ? -v : v;
}

// Why a letter other than the ones the reader knows (F G H I J K M N P R S T X Y Z) is refused.
std::string refused_letter(char letter) {
  const std::string l(1, letter);
  if (letter == 'A' || letter == 'B' || letter == 'C' || letter == 'U' || letter == 'V' || letter == 'W')
    return "axis " + l + " is not supported (the verifier simulates 3-axis X Y Z programs)";
  if (letter == 'O') return "O-words (subroutines) are not supported";
  if (letter == 'D') return "D (cutter radius compensation) is not supported";
  return "word " + l + " is not supported by the verifier";
}

Block parse_block(std::string_view text, const Place& where) {
  Block b;
  size_t i = 0;
  if (!text.empty() && text[0] == '/') throw Error(where.str(), "block delete '/' is not supported");
  while (i < text.size()) {
    const char letter = text[i];
    if (letter < 'A' || letter > 'Z')
      throw Error(where.str(), std::string("unexpected '") + letter + "' (parameters and expressions are not supported)");
    if (std::string_view("FGHIJKMNPRSTXYZ").find(letter) == std::string_view::npos)
      throw Error(where.str(), refused_letter(letter));
    ++i;
    const double v = parse_number(text, i, where, letter);
    if (letter == 'G' || letter == 'M') {
      int& n = letter == 'G' ? b.ng : b.nm;
      if (n == Block::kMaxCodes) throw Error(where.str(), std::string("more than 8 ") + letter + " words in one line");
      (letter == 'G' ? b.g : b.m)[n++] = static_cast<int>(std::lround(letter == 'G' ? v * 10 : v));
      continue;
    }
    if (b.has_word(letter) && letter != 'N') throw Error(where.str(), std::string("word ") + letter + " appears twice");
    b.has |= 1u << (letter - 'A');
    b.value[letter - 'A'] = v;
  }
  return b;
}

std::string gname(int g10) {
  std::string s = "G" + std::to_string(g10 / 10);
  if (g10 % 10) s += "." + std::to_string(g10 % 10);
  return s;
}

// The interpreter's modal state while reading.
class Reader {
 public:
  Reader(const std::string& name, const ToolSetup& tools, size_t expected_moves)
      : name_(name), tools_(tools) {
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
    place_.line = number;
    strip_comments(raw, text_, place_);
    if (text_.empty()) return true;
    if (text_[0] == '%') {
      if (percent_ || number_ > 0) return false;  // the closing '%'
      percent_ = true;
      return true;
    }
    ++number_;
    const Block b = parse_block(text_, place_);
    int motion = -1;
    for (int k = 0; k < b.ng; ++k) modal_g(b.g[k], motion);
    if (b.has_word('T')) select(b.word('T'));
    bool end = false;
    for (int k = 0; k < b.nm; ++k) end |= modal_m(b.m[k]);
    if (b.has_word('K')) throw Error(where(), "K is not supported in the XY plane (G17)");
    if (motion >= 0) motion_ = motion == 800 ? -1 : motion;
    if (b.has_axis()) {
      if (motion_ < 0) throw Error(where(), "axis words without a motion mode (G0, G1, G2 or G3)");
      move(b, number);
    } else if (motion == 20 || motion == 30) {
      throw Error(where(), gname(motion) + " without an end point");
    }
    return !end;
  }

  MachineProgram finish() {
    program_.from_gcode = true;
    return std::move(program_);
  }

 private:
  void modal_g(int g, int& motion) {
    switch (g) {
      case 0: case 10: case 20: case 30: case 800:
        if (motion >= 0) throw Error(where(), gname(motion) + " and " + gname(g) + " in one line");
        motion = g;
        return;
      case 170: return;
      case 200: scale_ = 25.4; return;
      case 210: scale_ = 1.0; return;
      case 900: absolute_ = true; return;
      case 910: absolute_ = false; return;
      case 901: absolute_arc_ = true; return;
      case 911: absolute_arc_ = false; return;
      case 40: return;  // dwell: P is a time, no axis words
      case 400: case 490: case 430: case 540: case 610: case 611: case 640: case 930: case 940: case 950: case 960:
      case 970: case 980: case 990:
        // No motion: comp off, tool length (positions are tool tips), G54, path control, feed and spindle modes,
        // canned-cycle return (canned cycles themselves are refused).
        return;
      default:
        throw Error(where(), gname(g) + " is not supported by the verifier (it would change the motion)");
    }
  }

  // Returns true for a program end (M2, M30).
  bool modal_m(int m) {
    if (m == 98 || m == 99) throw Error(where(), "M" + std::to_string(m) + " (subroutines) is not supported");
    if (m >= 70 && m <= 73)
      throw Error(where(), "M" + std::to_string(m) + " (saved modal state) is not supported by the verifier");
    if (m == 6) {
      if (selected_ < 0) throw Error(where(), "M6 without a T word before it");
      current_ = tool_index(selected_, where());
      return false;
    }
    const bool known = (m >= 0 && m <= 9) || m == 30 || m == 60 || (m >= 48 && m <= 53) || (m >= 62 && m <= 68) ||
                       (m >= 100 && m <= 199);
    if (!known) throw Error(where(), "M" + std::to_string(m) + " is not known to the verifier");
    return m == 2 || m == 30;
  }

  void select(double t) {
    const long n = std::lround(t);
    if (t != n || n < 0) throw Error(where(), "bad tool number T" + std::to_string(t));
    if (!tools_.tools.count(static_cast<int>(n)))
      throw Error(where(), "tool T" + std::to_string(n) + " is not in the tool table");
    selected_ = static_cast<int>(n);
  }

  int tool_index(int number, const std::string& where) {
    auto it = tools_.tools.find(number);
    if (it == tools_.tools.end()) throw Error(where, "tool T" + std::to_string(number) + " is not in the tool table");
    for (size_t i = 0; i < program_.tools.size(); ++i)
      if (program_.tools[i].id == number && (i > 0 || !tools_.loaded)) return static_cast<int>(i);
    Tool t = it->second;
    t.id = number;
    program_.tools.push_back(t);
    return static_cast<int>(program_.tools.size() - 1);
  }

  double axis(const Block& b, char c, int k) {
    if (!b.has_word(c)) return pos_[k];
    const double v = b.word(c) * scale_;
    if (absolute_) {
      known_ |= 1 << k;
      return v;
    }
    return pos_[k] + v;  // relative to an unknown position stays unknown
  }

  void move(const Block& b, uint32_t number) {
    const bool started = known_ == 7;
    const Vec3 to(axis(b, 'X', 0), axis(b, 'Y', 1), axis(b, 'Z', 2));
    const bool arc = motion_ == 20 || motion_ == 30;
    if (arc && !started) throw Error(where(), "an arc cannot be the first move (its start is unknown)");
    if (arc && b.has_word('P') && std::lround(b.word('P')) != 1)
      throw Error(where(), "arcs of several turns (P) are not supported");
    if (known_ != 7) {  // still somewhere unknown: nothing to sweep yet
      pos_ = to;
      return;
    }
    if (current_ < 0)
      throw Error(where(), "a move before any tool change (T.. M6) and no tool given for the one in the spindle at "
                          "the start (--tool)");
    SimMove m;
    m.from = started ? pos_ : to;
    m.to = to;
    m.tool = static_cast<uint16_t>(current_);
    m.source = number;
    m.rapid = motion_ == 0;
    if (arc) {
      m.shape = motion_ == 20 ? MoveShape::ArcCW : MoveShape::ArcCCW;
      m.centre = arc_centre(b, m);
    } else if (started && (m.to - m.from).squaredNorm() == 0.0) {
      return;  // a zero-length line leaves the cutter where it is
    }
    if (program_.moves.size() >= kMaxProgramMoves)
      throw Error(where(), "the program has more than " + std::to_string(kMaxProgramMoves) +
                              " moves, more than the verifier holds: verify it in parts");
    pos_ = to;
    program_.moves.push_back(m);
  }

  Vec2 arc_centre(const Block& b, const SimMove& m) const {
    const Vec2 a = m.from.head<2>(), e = m.to.head<2>();
    Vec2 c;
    if (b.has_word('R')) {
      if (b.has_word('I') || b.has_word('J')) throw Error(where(), "arc with both R and I/J");
      const double r = b.word('R') * scale_;
      const Vec2 chord = e - a;
      const double len = chord.norm();
      if (len == 0.0) throw Error(where(), "a full circle cannot be given with R");
      if (len > 2 * std::abs(r) + 1e-6) throw Error(where(), "arc radius R is smaller than half the chord");
      const double h = std::sqrt(std::max(0.0, r * r - 0.25 * len * len));
      const Vec2 right(chord.y() / len, -chord.x() / len);
      // G2 with R > 0 (arc up to half a turn) has its centre right of the chord; R < 0 or G3 flip the side.
      const double side = (m.shape == MoveShape::ArcCW ? 1.0 : -1.0) * (r > 0 ? 1.0 : -1.0);
      c = 0.5 * (a + e) + side * h * right;
    } else {
      if (!b.has_word('I') && !b.has_word('J')) throw Error(where(), "arc without I/J or R");
      const Vec2 ij(b.word('I') * scale_, b.word('J') * scale_);
      c = absolute_arc_ ? ij : Vec2(a + ij);
      const double r0 = (a - c).norm(), r1 = (e - c).norm();
      if (r0 == 0.0) throw Error(where(), "arc of zero radius");
      if (std::abs(r0 - r1) > 0.01 + 1e-3 * r0)
        throw Error(where(), "radius to the end of the arc differs from the radius to its start by " +
                                std::to_string(std::abs(r0 - r1)) + " mm");
    }
    return c;
  }

  std::string where() const { return place_.str(); }

  std::string name_, text_;
  Place place_{name_};
  const ToolSetup& tools_;
  MachineProgram program_;
  Vec3 pos_ = Vec3::Zero();
  int known_ = 0;  // bit per axis X, Y, Z once its position is known
  bool absolute_ = true, absolute_arc_ = false, percent_ = false;
  double scale_ = 1.0;
  int motion_ = -1, selected_ = -1, current_ = -1;
  uint32_t number_ = 0;  // blocks read
};

}  // namespace

MachineProgram parse_gcode(const std::string& text, const std::string& name, const ToolSetup& tools) {
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

MachineProgram read_gcode(const std::string& path, const ToolSetup& tools) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open the G-code program");
  in.seekg(0, std::ios::end);
  const auto bytes = in.tellg();
  in.seekg(0);
  // Room for about one move per 24 bytes (a typical motion line), at most 2 million ahead of need.
  Reader reader(path, tools, bytes > 0 ? std::min<size_t>(static_cast<size_t>(bytes) / 24, 2'000'000) : 0);
  uint32_t number = 0;
  for (std::string raw; std::getline(in, raw);)
    if (!reader.line(raw, ++number)) break;
  return reader.finish();
}

ToolSetup tool_setup(const std::vector<std::string>& specs, const ToolTable* table) {
  ToolSetup setup;
  if (table)
    for (const Tool& t : table->tools) setup.tools[t.id] = t;
  std::vector<int> defined;
  int loaded_number = -1;
  std::string loaded_spec;
  for (const std::string& spec : specs) {
    const std::string where = "--tool " + spec;
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

}  // namespace rosmill::verify
