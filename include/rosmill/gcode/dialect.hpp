// G-code dialects: what differs between controllers when the post-processor writes a program. Adding a
// controller is one row of the table in src/gcode/dialect.cpp.
#pragma once
#include <string>
#include <vector>

namespace rosmill::core::gcode {

struct Dialect {
  std::string name;
  std::string description;
  std::string setup_words;     // the safe modal start of every program (units, distance, plane, offset, ...)
  bool path_blending = false;  // G64 P<tolerance> (LinuxCNC's path blending within a tolerance)
  bool tool_change_m6 = false; // T<n> M6; otherwise the operator changes the tool at an M0 pause
  bool tool_length_offset = false;  // G43 H<n> after a tool change
  std::string program_end;     // M2 or M30
  size_t max_line_length = 0;  // 0: no limit (GRBL's line buffer holds 80 characters)
  // What the controller acts on inside a comment (comment_text.hpp): characters (beyond control bytes and bytes
  // above ASCII, always unsafe) and first words that turn a comment into an instruction.
  std::string comment_unsafe;
  std::vector<std::string> active_comments;
  bool coordinate_rotation = false;  // G10 L2 takes R: a work offset may turn the XY axes about Z
  // Simultaneous multi-axis programs: A and C words on every move, inverse time (G93) and the trunnion's
  // kinematics switches (M428, M429) of LinuxCNC's xyzac-trt configuration.
  bool tool_centre_point = false;
};

const std::vector<Dialect>& dialects();
// Throws Error listing the known names.
const Dialect& find_dialect(const std::string& name);

}  // namespace rosmill::core::gcode
