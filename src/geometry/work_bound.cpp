#include "rosmill/work_bound.hpp"

#include <cmath>
#include <cstdio>

#include "rosmill/error.hpp"

namespace rosmill::core {

void check_work(const std::string& where, const Work& work, double part_width, double part_depth) {
  const bool too_slow = !(work.queries <= kMaxDropQueries);
  const bool too_big = !(work.points <= kMaxHeldPoints);
  if (!too_slow && !too_big) return;
  char text[512];
  if (too_slow)
    std::snprintf(text, sizeof text, "would need about %.3g %s (limit %.3g)", work.queries, work.steps,
                  kMaxDropQueries);
  else
    std::snprintf(text, sizeof text, "would hold about %.3g points at once (limit %.3g)", work.points,
                  kMaxHeldPoints);
  std::string what = text;
  if (!work.counted.empty()) what += ", " + work.counted + ",";
  std::snprintf(text, sizeof text,
                " over a part of %.6g x %.6g mm: raise the stepover, step-down, spacing or tolerance, or check "
                "the cloud's units (or the mesh's)",
                part_width, part_depth);
  throw Error(where, what + text);
}

std::string count_text(double n, const char* what) {
  char text[64];
  std::snprintf(text, sizeof text, "%.3g ", n);
  return text + std::string(what);
}

double step_count(double length, double step) { return std::ceil(std::abs(length) / step) + 1.0; }

}  // namespace rosmill::core
