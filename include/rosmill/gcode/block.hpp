// Reading G-code back: one line into words, and the modal state a controller is in after each line. The limits
// checker walks a program with it, and a resumed program restores what it computes (units, distance mode,
// plane, work offset, tool, spindle, feed, coolant, motion mode and position).
#pragma once
#include <string>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::gcode {

struct Word {
  char letter;   // upper case
  double value;
};

struct Block {
  std::vector<Word> words;
  bool has(char letter) const;
  double get(char letter) const;  // NaN when absent
  // The G codes of the block, times ten (G91.1 -> 911), so that G codes with a decimal compare exactly.
  std::vector<int> g_codes() const;
  std::vector<int> m_codes() const;
};

// Parses one line (comments in parentheses and after ';' dropped, line number kept as word N). Throws Error
// naming `where` on a malformed word.
Block parse_block(const std::string& line, const std::string& where);

struct ModalState {
  bool metric = true;        // G21 / G20
  bool absolute = true;      // G90 / G91
  int plane = 17;            // 17, 18, 19
  int work_offset = 54;      // 54..59
  int motion = -1;           // 0, 1, 2, 3; -1 before any motion word
  double feed = 0.0;         // mm/min
  double spindle_rpm = 0.0;
  int spindle = 5;           // 3, 4 or 5
  bool flood = false, mist = false;
  int tool = 0;              // the tool in the spindle (after M6; GRBL: the last T word)
  int length_offset = -1;    // H of G43, -1 when off (G49)
  Vec3 position = Vec3::Zero();  // mm, program coordinates
  bool known[3] = {false, false, false};
  bool ended = false;        // after M2 / M30
};

// What one block did to the machine.
struct BlockMotion {
  bool moved = false;
  int motion = -1;
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();
  bool from_known[3] = {false, false, false};
  bool to_known[3] = {false, false, false};
  Vec2 centre = Vec2::Zero();  // arcs in the XY plane, absolute
};

// Applies a block to the state (in the order a controller does: modes, tool, spindle, coolant, then motion).
// Throws Error naming `where` on what it cannot follow (arcs outside G17, R-format arcs, inverse-time feed).
BlockMotion apply_block(ModalState& state, const Block& block, const std::string& where);

// The modal state after lines [0, line_count) of a program.
ModalState state_before(const std::vector<std::string>& lines, size_t line_count);

}  // namespace rosmill::gcode
