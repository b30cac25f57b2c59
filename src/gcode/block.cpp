#include "rosmill/gcode/block.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "rosmill/error.hpp"

namespace rosmill::gcode {

bool Block::has(char letter) const {
  for (const Word& w : words)
    if (w.letter == letter) return true;
  return false;
}

double Block::get(char letter) const {
  for (const Word& w : words)
    if (w.letter == letter) return w.value;
  return NAN;
}

std::vector<int> Block::g_codes() const {
  std::vector<int> g;
  for (const Word& w : words)
    if (w.letter == 'G') g.push_back(static_cast<int>(std::lround(w.value * 10)));
  return g;
}

std::vector<int> Block::m_codes() const {
  std::vector<int> m;
  for (const Word& w : words)
    if (w.letter == 'M') m.push_back(static_cast<int>(std::lround(w.value)));
  return m;
}

namespace {

// A G-code number: [+-] digits [. digits]. Not strtod: "G0X9" must not read as the hexadecimal 0X9, and
// exponents, "inf" and "nan" are no G-code.
const char* parse_number(const char* p, const char* end, double& value) {
  const char* start = p;
  bool negative = false;
  if (p < end && (*p == '+' || *p == '-')) negative = *p++ == '-';
  double v = 0;
  int digits = 0;
  while (p < end && std::isdigit(static_cast<unsigned char>(*p))) {
    v = v * 10 + (*p++ - '0');
    ++digits;
  }
  if (p < end && *p == '.') {
    ++p;
    double scale = 0.1;
    while (p < end && std::isdigit(static_cast<unsigned char>(*p))) {
      v += (*p++ - '0') * scale;
      scale *= 0.1;
      ++digits;
    }
  }
  if (digits == 0) return start;
  value = negative ? -v : v;
  return p;
}

}  // namespace

Block parse_block(const std::string& line, const std::string& where) {
  Block b;
  const char* p = line.c_str();
  const char* end = p + line.size();
  while (p < end) {
    const char c = *p;
    if (c == ';') break;
    if (c == '(') {
      const char* close = static_cast<const char*>(std::memchr(p, ')', static_cast<size_t>(end - p)));
      if (!close) throw Error(where, "comment not closed: " + line);
      p = close + 1;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c)) || c == '%') {
      ++p;
      continue;
    }
    if (!std::isalpha(static_cast<unsigned char>(c))) throw Error(where, std::string("unexpected '") + c + "' in: " + line);
    const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    ++p;
    while (p < end && *p == ' ') ++p;
    double v = 0;
    const char* num_end = parse_number(p, end, v);
    if (num_end == p) throw Error(where, std::string("word ") + letter + " without a number in: " + line);
    b.words.push_back({letter, v});
    p = num_end;
  }
  return b;
}

BlockMotion apply_block(ModalState& s, const Block& b, const std::string& where) {
  BlockMotion bm;
  int motion_word = -1;
  for (int g : b.g_codes()) {
    switch (g) {
      case 0: case 10: case 20: case 30: motion_word = g / 10; break;
      case 170: case 180: case 190: s.plane = g / 10; break;
      case 200: s.metric = false; break;
      case 210: s.metric = true; break;
      case 900: s.absolute = true; break;
      case 910: s.absolute = false; break;
      case 540: case 550: case 560: case 570: case 580: case 590: s.work_offset = g / 10; break;
      case 430: s.length_offset = b.has('H') ? static_cast<int>(b.get('H')) : s.tool; break;
      case 490: s.length_offset = -1; break;
      case 800: s.motion = -1; break;
      case 930: throw Error(where, "inverse-time feed (G93) is not followed");
      default: break;  // G40, G64, G94, G91.1, G4 ...: no effect on where the tool goes
    }
  }
  const double scale = s.metric ? 1.0 : 25.4;
  if (b.has('F')) s.feed = b.get('F') * scale;
  if (b.has('S')) s.spindle_rpm = b.get('S');
  const bool grbl_style_tool = !b.has('M');
  for (int m : b.m_codes()) {
    switch (m) {
      case 3: case 4: case 5: s.spindle = m; break;
      case 6: if (b.has('T')) s.tool = static_cast<int>(b.get('T')); break;
      case 7: s.mist = true; break;
      case 8: s.flood = true; break;
      case 9: s.mist = s.flood = false; break;
      case 2: case 30: s.ended = true; s.spindle = 5; s.mist = s.flood = false; break;
      default: break;
    }
  }
  if (grbl_style_tool && b.has('T')) s.tool = static_cast<int>(b.get('T'));
  if (motion_word >= 0) s.motion = motion_word;
  const bool axes = b.has('X') || b.has('Y') || b.has('Z');
  // G10/G28/G53/G92 take axis words that are not a move of the program; skip them as moves.
  for (int g : b.g_codes())
    if (g == 100 || g == 280 || g == 300 || g == 530 || g == 920) return bm;
  if (!axes) return bm;
  if (s.motion < 0) throw Error(where, "axis words without a motion mode");
  bm.moved = true;
  bm.motion = s.motion;
  bm.from = s.position;
  for (int a = 0; a < 3; ++a) bm.from_known[a] = s.known[a];
  static const char letters[3] = {'X', 'Y', 'Z'};
  for (int a = 0; a < 3; ++a) {
    if (!b.has(letters[a])) continue;
    const double v = b.get(letters[a]) * scale;
    if (s.absolute) {
      s.position[a] = v;
      s.known[a] = true;
    } else {
      s.position[a] += v;
    }
  }
  bm.to = s.position;
  for (int a = 0; a < 3; ++a) bm.to_known[a] = s.known[a];
  if (s.motion == 2 || s.motion == 3) {
    if (s.plane != 17) throw Error(where, "arcs outside the XY plane (G17) are not followed");
    if (b.has('R')) throw Error(where, "radius-format arcs (R) are not followed; use I and J");
    bm.centre = bm.from.head<2>() + Vec2(std::isnan(b.get('I')) ? 0.0 : b.get('I') * scale,
                                          std::isnan(b.get('J')) ? 0.0 : b.get('J') * scale);
  }
  return bm;
}

ModalState state_before(const std::vector<std::string>& lines, size_t count) {
  ModalState s;
  for (size_t i = 0; i < count && i < lines.size(); ++i)
    apply_block(s, parse_block(lines[i], "line " + std::to_string(i + 1)), "line " + std::to_string(i + 1));
  return s;
}

}  // namespace rosmill::gcode
