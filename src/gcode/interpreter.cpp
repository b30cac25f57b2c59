#include "rosmill/gcode/interpreter.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/gcode/arc_centre.hpp"
#include "rosmill/gcode/lexer.hpp"

namespace rosmill::core::gcode {
namespace {

constexpr int kGroups = 16;
constexpr int kNonModal = 0, kMotion = 1, kLength = 8;

// The modal group of a G code (times ten) in RS274/NGC (NIST version 3, table 4, with LinuxCNC's additions);
// -1 for no G code of the language.
int modal_group(int g) {
  switch (g) {
    case 0: case 10: case 20: case 30: case 330: case 382: case 383: case 384: case 385: case 730: case 760:
    case 800: case 810: case 820: case 830: case 840: case 850: case 860: case 870: case 880: case 890:
      return kMotion;
    case 40: case 100: case 280: case 281: case 300: case 301: case 530: case 920: case 921: case 922: case 923:
      return kNonModal;
    case 170: case 171: case 180: case 181: case 190: case 191: return 2;
    case 900: case 910: return 3;
    case 901: case 911: return 4;
    case 930: case 940: case 950: return 5;
    case 200: case 210: return 6;
    case 400: case 410: case 411: case 420: case 421: return 7;
    case 430: case 431: case 432: case 490: return kLength;
    case 980: case 990: return 10;
    case 540: case 550: case 560: case 570: case 580: case 590: case 591: case 592: case 593: return 12;
    case 610: case 611: case 640: return 13;
    case 960: case 970: return 14;
    case 70: case 80: return 15;
    default: return -1;
  }
}

bool followed_motion(int g) { return g == 0 || g == 10 || g == 20 || g == 30 || g == 800; }

// Group-0 codes whose axis words are not a move of the program.
bool takes_axis_words(int g) { return g == 100 || g == 280 || g == 300 || g == 920; }

constexpr char kAxisLetter[3] = {'X', 'Y', 'Z'};
constexpr char kOffsetLetter[3] = {'I', 'J', 'K'};

}  // namespace

Interpreter::Interpreter(std::string file) : file_(std::move(file)) { place_.file = file_; }

const Block& Interpreter::lex(std::string_view line, size_t number) {
  place_.line = number;
  moved_ = false;
  code_of(line, code_, place_);
  read_words(code_, place_, block_);
  return block_;
}

const Block& Interpreter::read(std::string_view line, size_t number) {
  lex(line, number);
  execute();
  return block_;
}

void Interpreter::execute() {
  moved_ = false;
  if (block_.percent) {
    if (percent_open_ || blocks_read_) state_.ended = true;  // the closing '%': the program ends there
    percent_open_ = true;
    return;
  }
  if (block_.empty()) return;
  blocks_read_ = true;
  // The order of execution within a block (NIST version 3, table 8): modes, then feed, speed, tool and the
  // machine's M codes, offsets, the non-modal codes, the motion, and the program end last.
  modal_codes();
  machine_words();
  non_modal_codes();
  motion();
  if (block_.m_count && (block_.has_m(2) || block_.has_m(30))) program_end();
}

void Interpreter::modal_codes() {
  int seen[kGroups];
  std::fill(seen, seen + kGroups, -1);
  for (int k = 0; k < block_.g_count; ++k) {
    const int g = block_.g[k], group = modal_group(g);
    if (group < 0) throw Error(where(), g_name(g) + " is not an RS274/NGC G code");
    if (seen[group] >= 0)
      throw Error(where(), g_name(seen[group]) + " and " + g_name(g) + " in one line (codes of one modal group)");
    seen[group] = g;
  }
  motion_word_ = seen[kMotion];
  non_modal_ = seen[kNonModal];
  length_word_ = seen[kLength];
  if (motion_word_ >= 0 && !followed_motion(motion_word_))
    throw Error(where(), g_name(motion_word_) + " is not followed by the reader (threading, probing, canned cycles)");
  for (int k = 0; k < block_.g_count; ++k) {
    const int g = block_.g[k];
    switch (g) {
      case 170: case 180: case 190: state_.plane = g / 10; break;
      case 171: case 181: case 191: throw Error(where(), g_name(g) + " (a UVW plane) is not followed by the reader");
      case 200: state_.metric = false; break;
      case 210: state_.metric = true; break;
      case 900: state_.absolute = true; break;
      case 910: state_.absolute = false; break;
      case 901: state_.absolute_arc = true; break;
      case 911: state_.absolute_arc = false; break;
      case 930: case 940: case 950: state_.feed_mode = g / 10; break;
      case 540: case 550: case 560: case 570: case 580: case 590: state_.work_offset = g / 10; break;
      case 591: case 592: case 593: state_.work_offset = g; break;
      default: break;  // cutter compensation, path control, spindle modes, canned-cycle return: no position
    }
  }
}

void Interpreter::machine_words() {
  const double unit = state_.metric ? 1.0 : 25.4;
  // Inverse time (G93): F is 1 / minutes for the move, whatever the length units.
  if (block_.has('F')) state_.feed = block_.get('F') * (state_.feed_mode == 93 ? 1.0 : unit);
  if (block_.has('S')) state_.spindle_rpm = block_.get('S');
  if (block_.has('T')) state_.selected_tool = static_cast<int>(std::lround(block_.get('T')));
  if (block_.has_m(6) && state_.selected_tool >= 0) state_.tool = state_.selected_tool;
  for (int k = 0; k < block_.m_count; ++k) {
    switch (block_.m[k]) {
      case 3: case 4: case 5: state_.spindle = block_.m[k]; break;
      case 7: state_.mist = true; break;
      case 8: state_.flood = true; break;
      case 9: state_.mist = state_.flood = false; break;
      default: break;
    }
  }
  // The length offset after the tool change (table 8): G43 without H takes the tool just loaded.
  if (length_word_ == 490) {
    state_.length_offset = -1;
  } else if (length_word_ >= 0) {
    state_.length_offset = block_.has('H') ? static_cast<int>(std::lround(block_.get('H'))) : state_.tool;
  }
}

void Interpreter::non_modal_codes() {
  const double unit = state_.metric ? 1.0 : 25.4;
  switch (non_modal_) {
    case 280: case 300: case 921: case 922: case 923:
      // Home through a point to a stored position, or origin offsets cleared or restored: no axis is known.
      std::fill(state_.known, state_.known + 3, false);
      return;
    case 100: {
      // Coordinate system data (L2, L20) moves the program's origin along the axes given.
      const long l = block_.has('L') ? std::lround(block_.get('L')) : -1;
      if (l == 2 || l == 20)
        for (int a = 0; a < 3; ++a) state_.known[a] = state_.known[a] && !block_.has(kAxisLetter[a]);
      // LinuxCNC's R turns the XY axes: both move.
      if (l == 2 && block_.has('R')) state_.known[0] = state_.known[1] = false;
      return;
    }
    case 920:
      // G92: the current point takes the coordinates given.
      for (int a = 0; a < 3; ++a)
        if (block_.has(kAxisLetter[a])) {
          state_.position[a] = block_.get(kAxisLetter[a]) * unit;
          state_.known[a] = true;
        }
      return;
    default: return;
  }
}

void Interpreter::motion() {
  if (motion_word_ >= 0) state_.motion = motion_word_ == 800 ? -1 : motion_word_ / 10;
  const bool arc_word = motion_word_ == 20 || motion_word_ == 30;
  if (!block_.has_axis() || (non_modal_ >= 0 && takes_axis_words(non_modal_))) {
    if (arc_word && !block_.has_axis()) throw Error(where(), g_name(motion_word_) + " without an end point");
    return;
  }
  if (state_.motion < 0) throw Error(where(), "axis words without a motion mode (G0, G1, G2 or G3)");
  if (non_modal_ == 530) {  // machine coordinates: the program's position along these axes is not known
    for (int a = 0; a < 3; ++a) state_.known[a] = state_.known[a] && !block_.has(kAxisLetter[a]);
    return;
  }
  CanonMove& m = move_;
  m.shape = MoveShape::Line;  // the fields an arc sets, back to a line's
  m.plane = Plane::XY;
  m.turns = 1;
  m.centre = Vec2::Zero();
  m.from = state_.position;
  m.known_from = static_cast<uint8_t>(state_.known[0] | state_.known[1] << 1 | state_.known[2] << 2);
  const double unit = state_.metric ? 1.0 : 25.4;
  for (int a = 0; a < 3; ++a) {
    if (!block_.has(kAxisLetter[a])) continue;
    const double v = block_.value[kAxisLetter[a] - 'A'] * unit;
    if (state_.absolute) {
      state_.position[a] = v;
      state_.known[a] = true;
    } else {
      state_.position[a] += v;  // relative to an unknown position stays unknown
    }
  }
  m.to = state_.position;
  m.known_to = static_cast<uint8_t>(state_.known[0] | state_.known[1] << 1 | state_.known[2] << 2);
  rotary(m);
  m.rapid = state_.motion == 0;
  m.feed = m.rapid ? 0.0f : static_cast<float>(state_.feed);
  if (!m.rapid && state_.feed_mode == 93) inverse_time_feed(m);
  m.source = static_cast<uint32_t>(place_.line);
  if (state_.motion == 2 || state_.motion == 3) {
    if (!m.from_known()) throw Error(where(), "an arc cannot be the first move (its start is unknown)");
    m.shape = state_.motion == 2 ? MoveShape::ArcCW : MoveShape::ArcCCW;
    m.plane = state_.plane == 18 ? Plane::ZX : state_.plane == 19 ? Plane::YZ : Plane::XY;
    arc(m);
  }
  moved_ = true;
}

// Inverse time (G93, NIST version 3, 3.5.19): the move takes 1/F minutes, and every feed move gives its own F. Its
// feed in mm/min is then F times its length, as LinuxCNC's canonical SET_FEED_RATE says: the linear axes' length, or
// the rotary axes' (degrees) for a move of those alone.
void Interpreter::inverse_time_feed(CanonMove& m) const {
  if (!block_.has('F')) throw Error(where(), "a feed move under inverse time (G93) without its F word");
  if (state_.motion == 2 || state_.motion == 3) throw Error(where(), "an arc under inverse time (G93) is not followed");
  double length = (m.to - m.from).norm();
  if (!(m.known_from == 7 && m.known_to == 7)) throw Error(where(), "an inverse-time move (G93) from an unknown place");
  if (length <= 0) length = std::hypot(m.a_to - m.a_from, m.c_to - m.c_from);
  m.feed = static_cast<float>(state_.feed * length);
}

// The rotary axes A and C: degrees whatever the length units, absolute or incremental as the linear axes. A
// move that turns them alongside linear axes is a simultaneous (5-axis) move the reader leaves to its consumers.
void Interpreter::rotary(CanonMove& m) {
  m.a_from = state_.a;
  m.c_from = state_.c;
  const auto turn = [&](char letter, double& at, bool& known) {
    if (!block_.has(letter)) return;
    if (state_.motion == 2 || state_.motion == 3)
      throw Error(where(), std::string(1, letter) + " on an arc: the reader follows arcs of the linear axes only");
    const double v = block_.get(letter);
    if (state_.absolute) {
      at = v;
      known = true;
    } else {
      at += v;
    }
  };
  turn('A', state_.a, state_.known_a);
  turn('C', state_.c, state_.known_c);
  m.a_to = state_.a;
  m.c_to = state_.c;
  m.known_rotary = static_cast<uint8_t>(state_.known_a | state_.known_c << 1);
}

void Interpreter::arc(CanonMove& m) const {
  const PlaneAxes ax = plane_axes(m.plane);
  if (block_.has(kOffsetLetter[ax.normal]))
    throw Error(where(), std::string(1, kOffsetLetter[ax.normal]) + " is not allowed for an arc in the G" +
                             std::to_string(state_.plane) + " plane");
  ArcWords w;
  w.start = Vec2(m.from[ax.first], m.from[ax.second]);
  w.end = Vec2(m.to[ax.first], m.to[ax.second]);
  w.clockwise = m.shape == MoveShape::ArcCW;
  w.unit = state_.metric ? 1.0 : 25.4;
  w.has_radius = block_.has('R');
  w.radius = block_.get('R');
  w.has_offset[0] = block_.has(kOffsetLetter[ax.first]);
  w.has_offset[1] = block_.has(kOffsetLetter[ax.second]);
  w.offset = Vec2(w.has_offset[0] ? block_.get(kOffsetLetter[ax.first]) : 0.0,
                  w.has_offset[1] ? block_.get(kOffsetLetter[ax.second]) : 0.0);
  w.absolute_centre = state_.absolute_arc;
  m.centre = arc_centre(w, place_);
  if (block_.has('P')) {
    const double p = block_.get('P');
    if (p != std::round(p) || p < 1 || p > 255)
      throw Error(where(), "the turns P of an arc must be a whole number from 1 to 255");
    m.turns = static_cast<uint8_t>(p);
  }
}

void Interpreter::program_end() {
  // M2 / M30 reset what LinuxCNC resets at a program end (NIST version 3, "program end").
  state_.ended = true;
  state_.plane = 17;
  state_.absolute = true;
  state_.feed_mode = 94;
  state_.work_offset = 54;
  state_.spindle = 5;
  state_.mist = state_.flood = false;
  state_.motion = 1;
}

std::string work_offset_code(int work_offset) {
  return g_name(work_offset < 100 ? work_offset * 10 : work_offset);
}

ModalState state_before(const std::vector<std::string>& lines, size_t count) {
  Interpreter reader;
  for (size_t i = 0; i < count && i < lines.size(); ++i) reader.read(lines[i], i + 1);
  return reader.state();
}

}  // namespace rosmill::core::gcode
