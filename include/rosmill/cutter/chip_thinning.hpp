// The feed for the radial engagement a cut actually has: radial chip thinning.
//
// A tooth that cuts an arc of phi of the cutter's circumference (the radial engagement angle) makes a chip whose
// largest thickness is h = fz * sin(phi) while phi < 90 degrees, and fz itself from 90 degrees on (Sandvik
// Coromant's milling formulas: maximum chip thickness hex = fz * sqrt(1 - (1 - 2 ae / D)^2), the same for a side cut
// of width ae, where cos(phi) = 1 - 2 ae / D; Machinery's Handbook, "radial chip thinning"). The tool table's feed
// holds at the tool's stated engagement phi_ref; keeping the chip as thick at phi gives
//     F(phi) = F_ref * sin(min(phi_ref, 90)) / sin(min(phi, 90)),
// lower in a slot than in a light side cut, higher in a lighter one. The rise is capped: at kMaxFeedFactor times
// the table's feed (the tool's rigidity and the machine's following error, which thinning does not see) and at the
// machine's largest feed; below kAirEngagementDeg the cutter is as good as in air and runs at the cap.
#pragma once
#include "rosmill/cutter/cutter.hpp"

namespace rosmill::core {

constexpr double kMaxFeedFactor = 3.0;     // the feed rises at most to three times the tool table's
constexpr double kAirEngagementDeg = 2.0;  // an engagement below this counts as air

// The feed (mm/min) for `engagement_deg` in [0, 180] by radial chip thinning from the tool's feed and its
// feed_engagement_deg(), capped at kMaxFeedFactor * tool.feed and at `max_feed` (mm/min; 0: no machine cap).
// Throws Error naming the value for an engagement outside [0, 180] or NaN, or a negative or NaN max_feed.
double feed_for_engagement(const Tool& tool, double engagement_deg, double max_feed);

}  // namespace rosmill::core
