// A line of a picture's figures, printf-formatted with up to three numbers (the maps' legends).
#pragma once
#include <cstdio>
#include <string>

namespace rosmill::core::verify {

inline std::string formatted(const char* format, double a, double b = 0, double c = 0) {
  char buf[96];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

}  // namespace rosmill::core::verify
