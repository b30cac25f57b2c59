#include "rosmill/gcode/linuxcnc_ini.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "rosmill/error.hpp"
#include "rosmill/text_words.hpp"

namespace rosmill::core::gcode {

LinuxcncIni LinuxcncIni::read(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path, "cannot read the LinuxCNC configuration");
  std::ostringstream text;
  text << in.rdbuf();
  return parse(text.str(), path);
}

LinuxcncIni LinuxcncIni::parse(const std::string& text, const std::string& path) {
  LinuxcncIni ini;
  ini.path_ = path;
  std::istringstream in(text);
  std::string line, section;
  for (size_t number = 1; std::getline(in, line); ++number) {
    const std::string t = trimmed(line);
    if (t.empty() || t[0] == '#' || t[0] == ';') continue;
    if (t[0] == '[') {
      const size_t close = t.find(']');
      if (close == std::string::npos) throw Error(path + ":" + std::to_string(number), "section header without ']'");
      section = trimmed(t.substr(1, close - 1));
      continue;
    }
    const size_t eq = t.find('=');
    if (eq == std::string::npos) throw Error(path + ":" + std::to_string(number), "neither [SECTION] nor KEY = VALUE");
    // The first of a repeated key is its value (LinuxCNC's own reader finds the first).
    ini.values_.emplace(std::make_pair(section, trimmed(t.substr(0, eq))), trimmed(t.substr(eq + 1)));
  }
  return ini;
}

bool LinuxcncIni::has(const std::string& section, const std::string& key) const {
  return values_.count({section, key}) > 0;
}

const std::string& LinuxcncIni::text(const std::string& section, const std::string& key) const {
  const auto it = values_.find({section, key});
  if (it == values_.end()) throw Error(path_, "[" + section + "] " + key + " is missing");
  return it->second;
}

double LinuxcncIni::number(const std::string& section, const std::string& key) const {
  const std::string& t = text(section, key);
  size_t used = 0;
  double v = NAN;
  try {
    v = std::stod(t, &used);
  } catch (const std::exception&) {
  }
  if (used != t.size() || !std::isfinite(v))
    throw Error(path_, "[" + section + "] " + key + " = '" + t + "' is not a number");
  return v;
}

}  // namespace rosmill::core::gcode
