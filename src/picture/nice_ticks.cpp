#include "rosmill/picture/nice_ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rosmill/error.hpp"

namespace rosmill::core::picture {

double nice_step(double span, int max_ticks) {
  if (!(span > 0) || !std::isfinite(span) || max_ticks < 1)
    throw Error("axis ticks", "span " + std::to_string(span) + " and " + std::to_string(max_ticks) +
                                  " ticks: need a positive finite span and at least one tick");
  const double raw = span / max_ticks;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0})
    if (m * decade >= raw * (1 - 1e-9)) return m * decade;
  return 10 * decade;
}

std::vector<double> ticks(double lo, double hi, double step) {
  std::vector<double> out;
  const double slack = step * 1e-6;
  for (double k = std::ceil((lo - slack) / step); k * step <= hi + slack; ++k) out.push_back(k * step);
  return out;
}

std::string tick_label(double value, double step) {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  if (std::abs(value) < step * 1e-6) value = 0;  // no "-0"
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

}  // namespace rosmill::core::picture
