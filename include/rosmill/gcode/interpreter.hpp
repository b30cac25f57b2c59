// The one G-code reader: a line -> lexer -> block -> modal state update -> canonical move, after LinuxCNC's
// rs274ngc interpreter (Kramer, Proctor and Messina, "The NIST RS274NGC Interpreter - Version 3": modal groups
// in section 3.4, the order of execution within a block in table 8). It follows G0-G3 in any plane (arcs by
// centre or radius, helical, G90.1/G91.1), units, distance modes, feed, spindle, coolant, tool selection and
// change, length offsets and work offsets. What moves the machine where the reader cannot follow it (G10, G28,
// G30, G53, G92) makes no canonical move and leaves the axes it touches unknown; consumers that must not pass
// such a block look at the block's G codes. Canned cycles and other motion modes are refused. A block-delete
// line runs as with the operator's switch off; a consumer that must know looks at Block::block_delete.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "rosmill/gcode/block.hpp"
#include "rosmill/toolpath/canon_move.hpp"

namespace rosmill::core::gcode {

struct ModalState {
  bool metric = true;         // G21 / G20
  bool absolute = true;       // G90 / G91
  bool absolute_arc = false;  // G90.1 / G91.1 (I J K absolute or from the start)
  int plane = 17;             // 17, 18, 19
  int work_offset = 54;       // 54..59; 591..593 for G59.1..G59.3
  int feed_mode = 94;         // 93 inverse time, 94 per minute, 95 per revolution
  int motion = -1;            // 0, 1, 2, 3; -1 before any motion word and after G80
  double feed = 0.0;          // mm/min (the F word in the program's units); under G93 the F word, 1/minutes
  double spindle_rpm = 0.0;
  int spindle = 5;            // 3, 4 or 5
  bool flood = false, mist = false;
  int selected_tool = -1;     // the last T word
  int tool = 0;               // the tool in the spindle (after M6)
  int length_offset = -1;     // H of G43, -1 when off (G49)
  Vec3 position = Vec3::Zero();  // mm, program coordinates
  bool known[3] = {false, false, false};
  double a = 0, c = 0;        // degrees: the rotary axes of a trunnion table
  bool known_a = false, known_c = false;
  bool ended = false;         // after M2 / M30 or the closing '%'
};

class Interpreter {
 public:
  // `file` names the program in error places ("file:line"); empty: "line N".
  explicit Interpreter(std::string file = {});
  Interpreter(const Interpreter&) = delete;  // its place refers to its own file name
  Interpreter& operator=(const Interpreter&) = delete;

  // Lexes line `number` (1-based). Throws Error naming the line on a malformed one.
  const Block& lex(std::string_view line, size_t number);
  // Carries out the block lexed last: the modal state changes and, when it moves the machine, move() is set.
  // Throws Error naming the line on what RS274/NGC refuses or the reader cannot follow. A '%' line opens the
  // program (the first one, before any block) or ends it.
  void execute();
  // Both.
  const Block& read(std::string_view line, size_t number);

  const Block& block() const { return block_; }
  const ModalState& state() const { return state_; }
  bool moved() const { return moved_; }
  const CanonMove& move() const { return move_; }  // the last block's move (when moved())
  const Place& place() const { return place_; }
  std::string where() const { return place_.str(); }

 private:
  void modal_codes();
  void machine_words();
  void non_modal_codes();
  void motion();
  void arc(CanonMove& m) const;
  void rotary(CanonMove& m);
  void inverse_time_feed(CanonMove& m) const;
  void program_end();

  std::string file_, code_;
  Place place_;
  Block block_;
  ModalState state_;
  CanonMove move_;
  bool moved_ = false, percent_open_ = false, blocks_read_ = false;
  // The block's codes (times ten) of the motion group, of group 0 and of the tool length group; -1: none.
  int motion_word_ = -1, non_modal_ = -1, length_word_ = -1;
};

// The G code of a ModalState::work_offset: "G54", "G59.1".
std::string work_offset_code(int work_offset);

// The modal state after lines [0, line_count) of a program.
ModalState state_before(const std::vector<std::string>& lines, size_t line_count);

}  // namespace rosmill::core::gcode
