#include "rosmill/value_range.hpp"

#include <cmath>
#include <cstdio>

#include "rosmill/error.hpp"

namespace rosmill::core {

void check_range(double v, double lo, double hi, const std::string& where, const char* unit, Bound low) {
  const bool above_low = low == Bound::Open ? v > lo : v >= lo;
  if (std::isfinite(v) && above_low && v <= hi) return;
  char text[160];
  std::snprintf(text, sizeof text, "must lie in %c%.6g, %.6g] %s, got %.6g", low == Bound::Open ? '(' : '[', lo, hi,
                unit, v);
  throw Error(where, text);
}

}  // namespace rosmill::core
