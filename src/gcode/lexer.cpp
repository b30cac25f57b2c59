#include "rosmill/gcode/lexer.hpp"

#include <charconv>
#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::core::gcode {

void code_of(std::string_view line, std::string& code, const Place& where) {
  code.clear();
  bool in_comment = false;
  for (const char c : line) {
    if (in_comment) {
      if (c == ')') in_comment = false;
      else if (c == '(') throw Error(where.str(), "nested comment ('(' inside a comment)");
      continue;
    }
    if (c == '(') {
      in_comment = true;
      continue;
    }
    if (c == ';') break;
    if (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f') continue;
    code.push_back(c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c);
  }
  if (in_comment) throw Error(where.str(), "comment not closed with ')'");
}

std::string code_of(std::string_view line, const Place& where) {
  std::string code;
  code_of(line, code, where);
  return code;
}

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Why a character cannot start a word.
std::string not_a_word(char c) {
  if (c == '#' || c == '[') return std::string("unexpected '") + c + "' (parameters and expressions are not supported)";
  if (c == '*') return "checksums ('*') are not RS274/NGC";
  if (c == '%') return "'%' is allowed only alone on its line";
  if (c == '/') return "block delete '/' must come first in the line";
  return std::string("unexpected '") + c + "'";
}

// An RS274 number at code[i]: [+-] digits [. digits]. Not strtod: "G0X9" must not read as the hexadecimal 0X9,
// and exponents, "inf" and "nan" are no G-code.
double read_number(std::string_view code, size_t& i, char letter, const Place& where) {
  const size_t start = i;
  if (i < code.size() && (code[i] == '+' || code[i] == '-')) ++i;
  size_t digits = 0;
  while (i < code.size() && is_digit(code[i])) ++i, ++digits;
  if (i < code.size() && code[i] == '.') {
    ++i;
    while (i < code.size() && is_digit(code[i])) ++i, ++digits;
  }
  if (digits == 0) {
    if (i < code.size() && (code[i] == '#' || code[i] == '[')) throw Error(where.str(), not_a_word(code[i]));
    throw Error(where.str(), std::string("word ") + letter + " has no number");
  }
  const bool negative = code[start] == '-';
  const size_t first = code[start] == '+' || negative ? start + 1 : start;
  double v = 0;
  std::from_chars(code.data() + first, code.data() + i, v);
  return negative ? -v : v;
}

void add_word(Block& b, char letter, double v, const Place& where) {
  if (letter == 'G' || letter == 'M') {
    int& n = letter == 'G' ? b.g_count : b.m_count;
    if (n == Block::kMaxCodes)
      throw Error(where.str(), "more than " + std::to_string(Block::kMaxCodes) + " " + letter + " words in one line");
    (letter == 'G' ? b.g : b.m)[n++] = static_cast<int>(std::lround(letter == 'G' ? v * 10 : v));
    return;
  }
  if (b.has(letter)) {
    if (letter == 'N') throw Error(where.str(), "a line number N must come first in the line");
    throw Error(where.str(), std::string("word ") + letter + " appears twice");
  }
  b.present |= 1u << (letter - 'A');
  b.value[letter - 'A'] = v;
}

}  // namespace

void read_words(std::string_view code, const Place& where, Block& b) {
  b.g_count = b.m_count = 0;
  b.present = 0;
  b.block_delete = b.percent = false;
  size_t i = 0;
  if (!code.empty() && code[0] == '%') {
    if (code.size() > 1) throw Error(where.str(), not_a_word('%'));
    b.percent = true;
    return;
  }
  if (!code.empty() && code[0] == '/') {
    b.block_delete = true;
    ++i;
  }
  const size_t first_word = i;
  while (i < code.size()) {
    const char letter = code[i];
    if (letter < 'A' || letter > 'Z') throw Error(where.str(), not_a_word(letter));
    if (letter == 'O') throw Error(where.str(), "O-words (subroutines) are not supported");
    if (letter == 'N' && i != first_word) throw Error(where.str(), "a line number N must come first in the line");
    ++i;
    add_word(b, letter, read_number(code, i, letter, where), where);
  }
}

Block read_words(std::string_view code, const Place& where) {
  Block b;
  read_words(code, where, b);
  return b;
}

Block lex_line(std::string_view line, std::string& code, const Place& where) {
  code_of(line, code, where);
  return read_words(code, where);
}

Block lex_line(std::string_view line, const Place& where) {
  std::string code;
  return lex_line(line, code, where);
}

}  // namespace rosmill::core::gcode
