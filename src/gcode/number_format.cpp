#include "rosmill/gcode/number_format.hpp"

#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::core::gcode {

int64_t decimal_scale(int decimals) {
  static const int64_t scales[] = {1, 10, 100, 1000, 10000, 100000, 1000000};
  if (decimals < 0 || decimals > 6) throw Error("decimals", "must be between 0 and 6, got " + std::to_string(decimals));
  return scales[decimals];
}

int64_t to_fixed(double value, int decimals) {
  return static_cast<int64_t>(std::llround(value * static_cast<double>(decimal_scale(decimals))));
}

void append_fixed(std::string& out, int64_t fixed, int decimals) {
  // The sign comes from the rounded integer, so a value that rounds to zero never reads "-0".
  if (fixed < 0) out.push_back('-');
  uint64_t mag = fixed < 0 ? static_cast<uint64_t>(-fixed) : static_cast<uint64_t>(fixed);
  const uint64_t scale = static_cast<uint64_t>(decimal_scale(decimals));
  uint64_t whole = mag / scale, frac = mag % scale;
  char digits[24];
  int n = 0;
  do {
    digits[n++] = static_cast<char>('0' + whole % 10);
    whole /= 10;
  } while (whole);
  while (n) out.push_back(digits[--n]);
  if (frac == 0) return;
  int width = decimals;
  while (frac % 10 == 0) {  // trailing zeros carry no information
    frac /= 10;
    --width;
  }
  out.push_back('.');
  char f[8];
  for (int i = width - 1; i >= 0; --i) {
    f[i] = static_cast<char>('0' + frac % 10);
    frac /= 10;
  }
  out.append(f, width);
}

void append_word(std::string& out, char letter, double value, int decimals) {
  out.push_back(letter);
  append_fixed(out, to_fixed(value, decimals), decimals);
}

}  // namespace rosmill::core::gcode
