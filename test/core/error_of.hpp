// The message of the rosmill::core::Error a call throws, or "" when it throws none: what the tests of refusals
// compare with the expected reason.
#pragma once
#include <functional>
#include <string>

#include "rosmill/error.hpp"

inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const rosmill::core::Error& e) {
    return e.what();
  }
  return "";
}
