#include "rosmill/gcode/dialect.hpp"

#include <sstream>

#include "rosmill/error.hpp"

namespace rosmill::core::gcode {

// One row per controller. G40 (no cutter compensation), G49 (no length offset), G80 (no canned cycle) and G94
// (feed per minute) make the start state explicit whatever the previous program left behind.
const std::vector<Dialect>& dialects() {
  static const std::vector<Dialect> table = {
      {"linuxcnc", "LinuxCNC (rs274ngc): T M6 tool change, G43 length offset, G64 path blending",
       "G17 G21 G40 G49 G54 G80 G90 G94", true, true, true, "M30", 0, "();",
       // LinuxCNC's comments that act (the G-code overview of its manual: messages, logging, probe logging, debug
       // and print output, abort, Python): with one of these first words a name would show a message, open a file
       // or stop the program.
       {"MSG", "DEBUG", "PRINT", "LOG", "LOGOPEN", "LOGAPPEND", "LOGCLOSE", "PROBEOPEN", "PROBECLOSE", "ABORT", "PY",
        "PYRUN", "PYRELOAD"},
       true, true},
      {"grbl", "GRBL 1.1: no tool changer (M0 pause to change the tool), 80-character lines",
       "G17 G21 G40 G49 G54 G80 G90 G94", false, false, false, "M30", 80,
       // GRBL 1.1 takes its real-time commands ('?' status, '!' hold, '~' resume, and bytes above ASCII) from
       // anywhere in the stream, comments included ("Grbl v1.1 Commands", its manual); (MSG, ...) is shown.
       "();?!~", {"MSG"}, false, false},
  };
  return table;
}

const Dialect& find_dialect(const std::string& name) {
  for (const Dialect& d : dialects())
    if (d.name == name) return d;
  std::ostringstream known;
  for (const Dialect& d : dialects()) known << (known.tellp() > 0 ? ", " : "") << d.name;
  throw Error("dialect", "unknown dialect '" + name + "' (known: " + known.str() + ")");
}

}  // namespace rosmill::core::gcode
