#include "rosmill/cutter/chip_thinning.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rosmill/error.hpp"

namespace rosmill::core {
namespace {

// The chip's largest thickness per unit of feed per tooth at an engagement (degrees): sin(phi) below 90.
double thickness_factor(double engagement_deg) {
  return std::sin(std::min(engagement_deg, 90.0) * M_PI / 180.0);
}

}  // namespace

double feed_for_engagement(const Tool& tool, double engagement_deg, double max_feed) {
  if (!(engagement_deg >= 0 && engagement_deg <= 180))
    throw Error("engagement", "must lie in [0, 180] degrees, got " + std::to_string(engagement_deg));
  if (!(max_feed >= 0)) throw Error("max_feed", "must be 0 (none) or more mm/min, got " + std::to_string(max_feed));
  const double reference = tool.feed_engagement_deg();
  if (!(reference > 0 && reference <= 180))
    throw Error("tool " + std::to_string(tool.id) + " feed_engagement",
                "must lie in (0, 180] degrees, got " + std::to_string(reference));
  double cap = kMaxFeedFactor * tool.feed;
  if (max_feed > 0) cap = std::min(cap, max_feed);
  if (engagement_deg < kAirEngagementDeg) return cap;
  return std::min(cap, tool.feed * thickness_factor(reference) / thickness_factor(engagement_deg));
}

}  // namespace rosmill::core
