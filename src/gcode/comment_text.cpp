#include "rosmill/gcode/comment_text.hpp"

#include <algorithm>
#include <cctype>

#include "rosmill/text_words.hpp"

namespace rosmill::core::gcode {
namespace {

// The letters the text's first word starts with, in upper case: "MSG" of "msg,hello", what an active comment
// begins with.
std::string keyword(const std::string& text) {
  std::string word;
  for (const char c : first_word(text)) {
    if (!std::isalpha(static_cast<unsigned char>(c))) break;
    word.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  }
  return word;
}

}  // namespace

std::string comment_line(const Dialect& dialect, const std::string& text, size_t room) {
  std::string clean;
  clean.reserve(text.size());
  for (const char ch : text) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c >= 0x80) clean.push_back('_');
    else if (c < 0x20 || c == 0x7f || dialect.comment_unsafe.find(ch) != std::string::npos) clean.push_back(' ');
    else clean.push_back(ch);
  }
  const std::string word = keyword(clean);
  const auto& active = dialect.active_comments;
  if (!word.empty() && std::find(active.begin(), active.end(), word) != active.end()) clean = "- " + clean;
  if (room > 2 && clean.size() > room - 2) clean.resize(room - 2);
  return "(" + clean + ")";
}

}  // namespace rosmill::core::gcode
