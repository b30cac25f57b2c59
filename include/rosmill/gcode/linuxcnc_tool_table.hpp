// A LinuxCNC tool table ([EMCIO] TOOL_TABLE, e.g. sim_mm.tbl): one tool per line, "T5 P5 Z30 D10 ;comment", words in
// any order, the pocket P, the length offset Z, the diameter D and more. rosmill reads each tool's length offset, which
// G43 adds to Z (the cycle-time estimate's machine-coordinate moves run from the spindle).
#pragma once
#include <map>
#include <string>

namespace rosmill::core::gcode {

// Tool number -> length offset in the table's units times `mm_per_unit`. A line without a T word (blank, comment) is
// skipped; a tool without a Z word has no offset (0). Throws Error naming `name` and the line of a word that is not a
// number, a tool number out of range or given twice.
std::map<int, double> tool_lengths_from_table(const std::string& text, const std::string& name, double mm_per_unit);

}  // namespace rosmill::core::gcode
