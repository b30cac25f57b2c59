// Where the time of a registration or a fusion goes: wall seconds summed per named phase, in the order the
// phases first ran, for the reports and the benchmarks.
#pragma once
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace rosmill::core::scan {

using PhaseSeconds = std::vector<std::pair<std::string, double>>;

class PhaseClock {
 public:
  explicit PhaseClock(PhaseSeconds& out) : out_(out), last_(std::chrono::steady_clock::now()) {}
  // Charges the time since the previous lap (or the start) to `phase`.
  void lap(const std::string& phase) {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    for (auto& [name, seconds] : out_)
      if (name == phase) {
        seconds += s;
        return;
      }
    out_.emplace_back(phase, s);
  }

 private:
  PhaseSeconds& out_;
  std::chrono::steady_clock::time_point last_;
};

// "name 0.123 s, name 0.045 s".
std::string format_phases(const PhaseSeconds& phases);

}  // namespace rosmill::core::scan
