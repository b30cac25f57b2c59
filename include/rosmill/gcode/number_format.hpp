// Fast fixed-precision numbers for G-code words: no exponent, no trailing zeros, never "-0".
#pragma once
#include <cstdint>
#include <string>

namespace rosmill::core::gcode {

// 10^decimals, for decimals in [0, 6].
int64_t decimal_scale(int decimals);
// The value in units of 10^-decimals (what is written, so what a controller reads back).
int64_t to_fixed(double value, int decimals);
// Appends the fixed value (in units of 10^-decimals) as text: 12.5, -0.001, 0, 100.
void append_fixed(std::string& out, int64_t fixed, int decimals);
// Appends a word: letter then number rounded to `decimals`.
void append_word(std::string& out, char letter, double value, int decimals);

}  // namespace rosmill::core::gcode
