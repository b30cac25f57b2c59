// A LinuxCNC configuration file (INI): [SECTION] headers and KEY = VALUE lines, '#' and ';' comment lines (the
// format LinuxCNC's inifile reader takes: a key may repeat, the first one counts for a single value).
#pragma once
#include <map>
#include <string>
#include <utility>

namespace rosmill::core::gcode {

class LinuxcncIni {
 public:
  // Throws Error naming the file when it cannot be read, and the line of one that is neither.
  static LinuxcncIni read(const std::string& path);
  static LinuxcncIni parse(const std::string& text, const std::string& path);

  const std::string& path() const { return path_; }
  bool has(const std::string& section, const std::string& key) const;
  // The value's text; throws Error("FILE", "[SECTION] KEY is missing") without it.
  const std::string& text(const std::string& section, const std::string& key) const;
  // The value as a number; throws Error naming the file, section and key when it is missing or not a number.
  double number(const std::string& section, const std::string& key) const;

 private:
  std::string path_;
  std::map<std::pair<std::string, std::string>, std::string> values_;
};

}  // namespace rosmill::core::gcode
