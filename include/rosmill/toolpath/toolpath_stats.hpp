// Figures of a toolpath (lengths and an estimate of the time), for reports, the CLI and the ROS statistics.
#pragma once
#include <cstddef>

#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::core {

// Figures of a toolpath: lengths in mm, time in seconds at the moves' feeds (rapids at `rapid_feed`).
struct ToolpathStats {
  size_t moves = 0;
  double cutting_length = 0.0;
  double rapid_length = 0.0;
  double estimated_seconds = 0.0;
};
ToolpathStats toolpath_stats(const Toolpath& tp, double rapid_feed = 5000.0);

}  // namespace rosmill::core
