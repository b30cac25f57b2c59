// The one error type of the core: what went wrong and where (a file, a line, a parameter).
#pragma once
#include <stdexcept>
#include <string>

namespace rosmill::core {

class Error : public std::runtime_error {
 public:
  // `where` names the input (file path, "parameter stepover", "line 12", ...); `what` says what is wrong.
  Error(const std::string& where, const std::string& what)
      : std::runtime_error(where.empty() ? what : where + ": " + what), where_(where) {}
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

}  // namespace rosmill::core
