// One block (line) of an RS274/NGC program as the lexer reads it: the words by letter, the G and M codes in the
// order written, and the marks around the words (block delete, a '%' demarcation line). Every consumer of
// G-code (the machine-limits check, resume-from-line, the verifier, GRBL streaming, the rs274 comparison) reads
// this one type. After LinuxCNC's rs274ngc interpreter (Kramer, Proctor and Messina, "The NIST RS274NGC
// Interpreter - Version 3", section 3.3, format of a line).
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace rosmill::core::gcode {

// Where a line is, spelled out only when an error names it: "file:12", "line 12" without a file name, or the
// name alone when it says everything (line 0).
struct Place {
  std::string_view file;
  size_t line = 0;
  std::string str() const;
};

struct Block {
  static constexpr int kMaxCodes = 8;
  // Only the first g_count, m_count codes and the `present` letters' values are set (a block is made for every
  // line read: nothing else is cleared).
  int g[kMaxCodes];       // G numbers times ten, so that G codes with a decimal compare exactly (G91.1 -> 911)
  int m[kMaxCodes];       // M numbers
  int g_count = 0, m_count = 0;
  double value[26];       // the other words (line number N included), by letter
  uint32_t present = 0;   // bit per letter of `value`
  bool block_delete = false;  // the line starts with '/': skipped when the operator's block-delete switch is on
  bool percent = false;       // a '%' line, which demarcates the program in a file

  bool has(char letter) const { return present >> (letter - 'A') & 1u; }
  double get(char letter) const { return has(letter) ? value[letter - 'A'] : NAN; }  // NaN when absent
  bool has_axis() const { return has_linear() || has_rotary(); }
  bool has_linear() const { return has('X') || has('Y') || has('Z'); }
  bool has_rotary() const { return has('A') || has('C'); }  // the axes of a trunnion table (B is not followed)
  bool has_g(int g10) const;
  bool has_m(int number) const;
  bool empty() const { return g_count == 0 && m_count == 0 && present == 0; }
};

// "G91.1" for 911.
std::string g_name(int g10);

}  // namespace rosmill::core::gcode
