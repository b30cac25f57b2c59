// Axis ticks at "nice" numbers: steps of 1, 2 or 5 times a power of ten, the scheme of Heckbert's "Nice numbers
// for graph labels" (Graphics Gems, 1990), so a reader can interpolate between two labels at a glance.
#pragma once
#include <string>
#include <vector>

namespace rosmill::core::picture {

// The smallest step of 1, 2 or 5 x 10^k that puts at most `max_ticks` intervals on a span (> 0, finite).
double nice_step(double span, int max_ticks);
// The multiples of `step` within [lo, hi] (with a rounding allowance of a millionth of a step).
std::vector<double> ticks(double lo, double hi, double step);
// A tick's label with as many decimals as the step needs ("-0" written as "0").
std::string tick_label(double value, double step);

}  // namespace rosmill::core::picture
