// How much of a part a set of setups reaches, and a small set of 3-axis setups that reaches all of it.
#pragma once
#include <vector>

#include "rosmill/segment/egi.hpp"
#include "rosmill/segment/setup_filter.hpp"

namespace rosmill::core::segment {

// Area reached by at least one of the setups over the part's area (0 for a part without area).
double coverage(const EgiSet& egis, const std::vector<SetupFilter>& setups);

// A small list of the six axis setups that together reach everything the six reach (with 90 degrees: the whole
// part). Greedy set cover: repeatedly the setup adding the most unreached area (ties in the order of
// axis_setups()), so the list is small but not proven smallest.
std::vector<SetupFilter> greedy_axis_cover(const EgiSet& egis);

}  // namespace rosmill::core::segment
