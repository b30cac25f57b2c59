#include "rosmill/verify/gcode_reader.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "rosmill/error.hpp"

namespace rosmill::verify {
namespace {

// One block (line) of words after comments and spaces are removed.
struct Block {
  std::vector<int> g;            // G numbers times ten (G90.1 -> 901)
  std::vector<int> m;
  double value[26] = {};         // by letter
  bool has[26] = {};
  bool has_axis() const { return has['X' - 'A'] || has['Y' - 'A'] || has['Z' - 'A']; }
  bool has_word(char c) const { return has[c - 'A']; }
  double word(char c) const { return value[c - 'A']; }
};

std::string strip_comments(const std::string& raw, const std::string& where) {
  std::string out;
  bool in_paren = false;
  for (char c : raw) {
    if (in_paren) {
      if (c == ')') in_paren = false;
      continue;
    }
    if (c == '(') { in_paren = true; continue; }
    if (c == ';') break;
    if (std::isspace(static_cast<unsigned char>(c))) continue;
    out.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  }
  if (in_paren) throw Error(where, "comment not closed with ')'");
  return out;
}

// An RS274 number: optional sign, digits, optional point and digits (no exponent, no hex: "G0X5" is G0 X5).
double parse_number(const std::string& text, size_t& i, const std::string& where, char letter) {
  const size_t start = i;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  size_t digits = 0;
  while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i, ++digits;
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i, ++digits;
  }
  if (digits == 0) throw Error(where, std::string("word ") + letter + " has no number");
  return std::strtod(text.substr(start, i - start).c_str(), nullptr);
}

Block parse_block(const std::string& text, const std::string& where) {
  Block b;
  size_t i = 0;
  if (!text.empty() && text[0] == '/') throw Error(where, "block delete '/' is not supported");
  while (i < text.size()) {
    const char letter = text[i];
    if (letter < 'A' || letter > 'Z')
      throw Error(where, std::string("unexpected '") + letter + "' (parameters and expressions are not supported)");
    ++i;
    const double v = parse_number(text, i, where, letter);
    if (letter == 'G') {
      b.g.push_back(static_cast<int>(std::lround(v * 10)));
    } else if (letter == 'M') {
      b.m.push_back(static_cast<int>(std::lround(v)));
    } else if (letter == 'O') {
      throw Error(where, "O-words (subroutines) are not supported");
    } else {
      if (b.has[letter - 'A'] && letter != 'N') throw Error(where, std::string("word ") + letter + " appears twice");
      b.has[letter - 'A'] = true;
      b.value[letter - 'A'] = v;
    }
  }
  return b;
}

std::string gname(int g10) {
  std::ostringstream s;
  s << 'G' << g10 / 10;
  if (g10 % 10) s << '.' << g10 % 10;
  return s.str();
}

// The interpreter's modal state while reading.
class Reader {
 public:
  Reader(const std::string& name, const std::map<int, Tool>& tools) : name_(name), tools_(tools) {
    if (tools.empty()) throw Error(name, "no tool given for the G-code program (pass --tool, e.g. ball:6)");
    current_ = tool_index(tools.begin()->first, name);
  }

  void line(const std::string& raw, int number) {
    where_ = name_ + ":" + std::to_string(number);
    const std::string text = strip_comments(raw, where_);
    if (text.empty() || text[0] == '%') return;
    const Block b = parse_block(text, where_);
    int motion = -1;
    for (int g : b.g) modal_g(g, motion);
    if (b.has_word('T')) selected_ = static_cast<int>(std::lround(b.word('T')));
    for (int m : b.m) modal_m(m);
    if (b.has_word('K')) throw Error(where_, "K is not supported in the XY plane (G17)");
    if (motion >= 0) motion_ = motion;
    if (!b.has_axis()) {
      if (motion == 20 || motion == 30) throw Error(where_, gname(motion) + " without an end point");
      return;
    }
    if (motion_ < 0) throw Error(where_, "axis words without a motion mode (G0, G1, G2 or G3)");
    move(b, static_cast<uint32_t>(number));
  }

  MachineProgram finish() {
    program_.from_gcode = true;
    return std::move(program_);
  }

 private:
  void modal_g(int g, int& motion) {
    switch (g) {
      case 0: case 10: case 20: case 30: motion = g; return;
      case 170: return;
      case 200: scale_ = 25.4; return;
      case 210: scale_ = 1.0; return;
      case 900: absolute_ = true; return;
      case 910: absolute_ = false; return;
      case 901: absolute_arc_ = true; return;
      case 911: absolute_arc_ = false; return;
      case 40: return;  // dwell: P is a time, no axis words
      case 400: case 490: case 430: case 540: case 610: case 611: case 640: case 800: case 930: case 940: case 950:
        return;  // no motion: comp off, tool length (positions are tool tips), G54, path control, canned off, feed mode
      default:
        throw Error(where_, gname(g) + " is not supported by the verifier (it would change the motion)");
    }
  }

  void modal_m(int m) {
    if (m == 98 || m == 99) throw Error(where_, "M" + std::to_string(m) + " (subroutines) is not supported");
    if (m == 6) {
      if (selected_ < 0) throw Error(where_, "M6 without a T word before it");
      current_ = tool_index(selected_, where_);
    }
  }

  uint16_t tool_index(int number, const std::string& where) {
    auto it = tools_.find(number);
    if (it == tools_.end()) throw Error(where, "tool T" + std::to_string(number) + " is not in the tool list");
    for (size_t i = 0; i < program_.tools.size(); ++i)
      if (program_.tools[i].id == number) return static_cast<uint16_t>(i);
    Tool t = it->second;
    t.id = number;
    program_.tools.push_back(t);
    return static_cast<uint16_t>(program_.tools.size() - 1);
  }

  double axis(const Block& b, char c, double current) const {
    if (!b.has_word(c)) return current;
    const double v = b.word(c) * scale_;
    return absolute_ ? v : current + v;
  }

  void move(const Block& b, uint32_t number) {
    const Vec3 to(axis(b, 'X', pos_.x()), axis(b, 'Y', pos_.y()), axis(b, 'Z', pos_.z()));
    SimMove m;
    m.from = started_ ? pos_ : to;
    m.to = to;
    m.tool = current_;
    m.source = number;
    m.rapid = motion_ == 0;
    if (motion_ == 20 || motion_ == 30) {
      if (!started_) throw Error(where_, "an arc cannot be the first move (its start is unknown)");
      m.shape = motion_ == 20 ? MoveShape::ArcCW : MoveShape::ArcCCW;
      m.centre = arc_centre(b, m);
    } else if (started_ && (m.to - m.from).squaredNorm() == 0.0) {
      started_ = true;
      return;  // a zero-length line leaves the cutter where it is
    }
    if (b.has_word('P') && motion_ >= 20 && std::lround(b.word('P')) != 1)
      throw Error(where_, "arcs of several turns (P) are not supported");
    started_ = true;
    pos_ = to;
    program_.moves.push_back(m);
  }

  Vec2 arc_centre(const Block& b, const SimMove& m) const {
    const Vec2 a = m.from.head<2>(), e = m.to.head<2>();
    Vec2 c;
    if (b.has_word('R')) {
      if (b.has_word('I') || b.has_word('J')) throw Error(where_, "arc with both R and I/J");
      const double r = b.word('R') * scale_;
      const Vec2 chord = e - a;
      const double len = chord.norm();
      if (len == 0.0) throw Error(where_, "a full circle cannot be given with R");
      if (len > 2 * std::abs(r) + 1e-6) throw Error(where_, "arc radius R is smaller than half the chord");
      const double h = std::sqrt(std::max(0.0, r * r - 0.25 * len * len));
      const Vec2 right(chord.y() / len, -chord.x() / len);
      // G2 with R > 0 (arc up to half a turn) has its centre right of the chord; R < 0 or G3 flip the side.
      const double side = (m.shape == MoveShape::ArcCW ? 1.0 : -1.0) * (r > 0 ? 1.0 : -1.0);
      c = 0.5 * (a + e) + side * h * right;
    } else {
      if (!b.has_word('I') && !b.has_word('J')) throw Error(where_, "arc without I/J or R");
      const Vec2 ij(b.word('I') * scale_, b.word('J') * scale_);
      c = absolute_arc_ ? ij : Vec2(a + ij);
      const double r0 = (a - c).norm(), r1 = (e - c).norm();
      if (r0 == 0.0) throw Error(where_, "arc of zero radius");
      if (std::abs(r0 - r1) > 0.01 + 1e-3 * r0)
        throw Error(where_, "radius to the end of the arc differs from the radius to its start by " +
                                std::to_string(std::abs(r0 - r1)) + " mm");
    }
    return c;
  }

  std::string name_, where_;
  const std::map<int, Tool>& tools_;
  MachineProgram program_;
  Vec3 pos_ = Vec3::Zero();
  bool started_ = false;
  bool absolute_ = true, absolute_arc_ = false;
  double scale_ = 1.0;
  int motion_ = -1, selected_ = -1;
  uint16_t current_ = 0;
};

}  // namespace

MachineProgram parse_gcode(const std::string& text, const std::string& name, const std::map<int, Tool>& tools) {
  Reader reader(name, tools);
  std::istringstream in(text);
  int number = 0;
  for (std::string raw; std::getline(in, raw);) reader.line(raw, ++number);
  return reader.finish();
}

MachineProgram read_gcode(const std::string& path, const std::map<int, Tool>& tools) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open the G-code program");
  std::ostringstream s;
  s << in.rdbuf();
  return parse_gcode(s.str(), path, tools);
}

std::map<int, Tool> tools_from_specs(const std::vector<std::string>& specs) {
  std::map<int, Tool> tools;
  int next = 1;
  for (const std::string& spec : specs) {
    std::string body = spec;
    int number = next;
    const size_t eq = spec.find('=');
    if (eq != std::string::npos) {
      std::string key = spec.substr(0, eq);
      if (!key.empty() && (key[0] == 'T' || key[0] == 't')) key = key.substr(1);
      char* end = nullptr;
      const long n = std::strtol(key.c_str(), &end, 10);
      if (key.empty() || *end != '\0' || n < 0) throw Error("--tool " + spec, "bad tool number '" + key + "'");
      number = static_cast<int>(n);
      body = spec.substr(eq + 1);
    }
    Tool t;
    t.id = number;
    t.name = body;
    t.cutter = parse_cutter_spec(body, "--tool " + spec);
    if (tools.count(number)) throw Error("--tool " + spec, "tool T" + std::to_string(number) + " given twice");
    tools[number] = t;
    next = number + 1;
  }
  return tools;
}

}  // namespace rosmill::verify
