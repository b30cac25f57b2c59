// A G-code program as the simulator sees it: the canonical moves of the one reader (rosmill/gcode/interpreter.hpp)
// with the tools of the setup. It follows what the simulation models: G0/G1/G2/G3 in the XY plane (helical z
// allowed), G17, G20/G21, G90/G91, G90.1/G91.1, F, S, T with M6, comments, line numbers; M2 or M30 ends the
// program (the controller reads no further), as does a closing '%'. Words that do not move the tool (spindle,
// coolant, G54, G40, G49, G43, G64, G61, G93-G97, G98/G99, G4 dwell, pauses, user M-codes) are accepted and
// ignored. Anything else that would change the motion (G18/G19, cutter radius compensation, canned cycles,
// G28/G30/G53, G92, other work offsets, block delete, subroutines, parameters and expressions, P turns on arcs,
// rotary axes A/B/C, M70-M73) or a word the verifier does not know throws Error naming the file and line. On a
// trunnion table (ToolSetup::rotary) A and C are read too, each move carrying them (verify/indexed.hpp follows them),
// as is the G53 G0 retract before an indexing: the position it leaves is unknown, and the next move is swept from
// its own target. There M428 and M429 switch LinuxCNC's xyzac-trt to tool-centre-point kinematics and back: each
// move says which held (CanonMove::tool_centre_point).
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/stock/program.hpp"

namespace rosmill::core::verify {

// The tools a program may call by T number, and the one in the spindle when it starts (used until its first M6).
// Without a loaded tool, a move before any M6 is an error, unless the setup holds exactly one tool.
struct ToolSetup {
  std::map<int, Tool> tools;
  std::optional<Tool> loaded;
  bool rotary = false;  // the machine turns the part with A and C (a trunnion): their words are read
};

// The tool table's tools (when given) and the command line's --tool specs on top of them:
//   "N=CUTTER" or "TN=CUTTER"  defines tool N (CUTTER: ball:D, flat:D, bull:D:r; replaces the table's N)
//   "CUTTER@N"                 the same, as `rosmill plan --tool` names an inline tool
//   "CUTTER"                   the tool in the spindle at the start
//   "N" or "TN"                tool N is in the spindle at the start
// Throws Error naming the spec on a bad one, a tool defined twice, or two tools loaded at the start.
ToolSetup tool_setup(const std::vector<std::string>& specs, const ToolTable* table = nullptr);

// Programs larger than this many moves are refused (the moves are held in memory).
constexpr size_t kMaxProgramMoves = 20'000'000;

// Positions are unknown until an axis is first given; a move is swept once all three are known, the first one
// from its own target (the controller's position before the program is not known).
stock::MachineProgram parse_gcode(const std::string& text, const std::string& name, const ToolSetup& tools);
stock::MachineProgram read_gcode(const std::string& path, const ToolSetup& tools);

}  // namespace rosmill::core::verify
