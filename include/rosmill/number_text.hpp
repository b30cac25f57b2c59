// A number as messages and reports write it: fixed notation with a stated number of digits after the point.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <string>

namespace rosmill::core {

inline std::string decimal_text(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

// At most `digits` significant digits, in fixed or exponent notation as printf's %g chooses ("0.25", "1e+03").
inline std::string significant_text(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

// The fewest digits after the point (at most 17) that read back as exactly `value`, in fixed notation ("6.35", "10").
inline std::string shortest_text(double value) {
  char text[400];
  for (int digits = 0; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

}  // namespace rosmill::core
