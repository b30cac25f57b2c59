#include "rosmill/scan/phase_clock.hpp"

#include <cstdio>

namespace rosmill::core::scan {

std::string format_phases(const PhaseSeconds& phases) {
  std::string out;
  for (const auto& [name, seconds] : phases) {
    char figure[32];
    std::snprintf(figure, sizeof figure, " %.3f s", seconds);
    out += (out.empty() ? "" : ", ") + name + figure;
  }
  return out;
}

}  // namespace rosmill::core::scan
