#include "rosmill/gcode/linuxcnc_tool_table.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"

namespace rosmill::core::gcode {

std::map<int, double> tool_lengths_from_table(const std::string& text, const std::string& name, double mm_per_unit) {
  std::map<int, double> lengths;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    const std::string where = name + ":" + std::to_string(number);
    std::istringstream words(line.substr(0, line.find(';')));
    int tool = -1;
    double length = 0;
    for (std::string w; words >> w;) {
      const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(w[0])));
      if (letter == 'T') tool = parse_tool_number(w.substr(1), where);
      if (letter != 'Z') continue;
      char* end = nullptr;
      length = std::strtod(w.c_str() + 1, &end);
      if (w.size() < 2 || *end != '\0' || !std::isfinite(length))
        throw Error(where, "the length offset '" + w + "' is not a number");
    }
    if (tool < 0) continue;
    if (!lengths.emplace(tool, length * mm_per_unit).second)
      throw Error(where, "tool " + std::to_string(tool) + " is listed twice");
  }
  return lengths;
}

}  // namespace rosmill::core::gcode
