// Words of a line of text as the file formats read them (a LinuxCNC INI file, a PCD header, a controller's
// replies): white space is blanks, tabs and a carriage return left by a CRLF line end.
#pragma once
#include <string>

namespace rosmill::core {

inline constexpr const char* kBlanks = " \t\r";

// `s` without the white space at its ends.
inline std::string trimmed(const std::string& s) {
  const size_t first = s.find_first_not_of(kBlanks);
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(kBlanks) - first + 1);
}

// The first white-space-delimited word of `s` ("" for a blank line).
inline std::string first_word(const std::string& s) {
  const size_t start = s.find_first_not_of(kBlanks);
  if (start == std::string::npos) return {};
  return s.substr(start, s.find_first_of(kBlanks, start) - start);
}

}  // namespace rosmill::core
