// A small RS274 (LinuxCNC flavour) reader for what the simulator needs: G0/G1/G2/G3 in the XY plane (helical
// z allowed), G17, G20/G21, G90/G91, G90.1/G91.1, F, S, T with M6, comments, line numbers. Words that do not move
// the tool (spindle, coolant, G54, G40, G49, G43, G64, G61, G94, G4 dwell, program end) are accepted and ignored.
// Anything else that would change the motion (G18/G19, cutter radius compensation, canned cycles, G28/G30/G53,
// G92, subroutines, expressions, P turns on arcs) throws Error naming the file and line.
#pragma once
#include <map>
#include <string>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/verify/program.hpp"

namespace rosmill::verify {

// `tools` maps T numbers to tools. A program without a T word runs with the lowest-numbered tool; a T number
// that is not in the map throws Error naming the line. Positions before the first move are taken as 0, so the
// first move does not sweep from an unknown place: it starts at its own target.
MachineProgram parse_gcode(const std::string& text, const std::string& name, const std::map<int, Tool>& tools);
MachineProgram read_gcode(const std::string& path, const std::map<int, Tool>& tools);

// Tools given on the command line: "ball:6" (T1, T2, ... in order) or "T3=ball:6" / "3=ball:6".
std::map<int, Tool> tools_from_specs(const std::vector<std::string>& specs);

}  // namespace rosmill::verify
