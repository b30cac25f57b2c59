// Text that goes into a program (a title, a tool's name, a strategy's name, a file name) made inert for the
// dialect's controller: it can only ever be read as one comment on one line. Every comment the post-processor
// writes goes through comment_line.
#pragma once
#include <string>

#include "rosmill/gcode/dialect.hpp"

namespace rosmill::core::gcode {

// "(text)" with, for the dialect: line ends and other control bytes as spaces (a newline would start a block),
// bytes beyond ASCII as '_', the characters the controller acts on inside a comment as spaces (the comment's
// own delimiters; GRBL's real-time commands '?', '!', '~', which it takes from anywhere in the stream), and a
// leading word that would make the comment an instruction (LinuxCNC's MSG, DEBUG, PROBEOPEN, LOGOPEN, ...) set
// off by "- ". At most `room` characters in all when room > 2 (the text is cut; 0: no limit).
std::string comment_line(const Dialect& dialect, const std::string& text, size_t room = 0);

}  // namespace rosmill::core::gcode
