// Wall time since a moment, as the reports give their timings (seconds on the steady clock).
#pragma once
#include <chrono>

namespace rosmill::core {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rosmill::core
