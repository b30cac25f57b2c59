// The lexer of the one G-code reader, in LinuxCNC's two steps (rs274ngc: close_and_downcase, then parse_line):
// first the line's code (comments, spaces and the line end removed, letters in upper case), then its words.
//   - comments: "(...)" anywhere (not nested, closed on the same line) and ';' to the end of the line
//   - block delete: '/' before everything else
//   - line number: an N word, only first (after the '/')
//   - '%' lines: nothing but the '%' (comments aside); they demarcate the program in a file
//   - words: a letter and a number ([+-] digits [. digits], no exponent: "G0X9" is G0 X9); spaces anywhere, even
//     inside a number ("X 1 0" is X10); a letter at most once, G and M codes repeated
// Refused, naming the line: an unclosed or nested comment, a word without a number or twice, parameters and
// expressions ('#', '['), O-words (subroutines), checksums ('*', which rs274ngc does not read), other characters.
#pragma once
#include <string>
#include <string_view>

#include "rosmill/gcode/block.hpp"

namespace rosmill::core::gcode {

// The code of one line into `code` (cleared first). Throws Error at `where` on an unclosed or nested comment.
void code_of(std::string_view line, std::string& code, const Place& where);
std::string code_of(std::string_view line, const Place& where);

// The words of a line's code (what code_of gives), into `block` (a reader reuses one) or a new block.
void read_words(std::string_view code, const Place& where, Block& block);
Block read_words(std::string_view code, const Place& where);

// Both steps; `code` is scratch space that a caller reading many lines reuses.
Block lex_line(std::string_view line, std::string& code, const Place& where);
Block lex_line(std::string_view line, const Place& where);

}  // namespace rosmill::core::gcode
