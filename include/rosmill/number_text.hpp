// A number as messages and reports write it: fixed notation with a stated number of digits after the point.
#pragma once
#include <cstdio>
#include <string>

namespace rosmill::core {

inline std::string decimal_text(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

}  // namespace rosmill::core
