// Feeds from engagement (cutter/chip_thinning.hpp): the tool table's feed at its stated engagement, radial chip
// thinning away from it (h = fz sin(phi) below 90 degrees), capped; and the table's feed_engagement field.
#include <gtest/gtest.h>

#include <cmath>

#include "error_of.hpp"
#include "rosmill/cutter/chip_thinning.hpp"
#include "rosmill/cutter/tool_table.hpp"

using namespace rosmill::core;

namespace {

constexpr double kRad = M_PI / 180;

// The package's roughing end mill as its table row has it: 10 mm, feed 1500 at its 4 mm stepover.
Tool roughing_tool() {
  Tool t = default_tool(Cutter::flat(10));
  t.feed = 1500;
  t.stepover = 4;
  return t;
}

}  // namespace

TEST(ChipThinning, StepoverEngagementIsTheDefaultReference) {
  const Tool t = roughing_tool();
  EXPECT_NEAR(t.feed_engagement_deg(), std::acos(1 - 4.0 / 5) / kRad, 1e-12);  // 78.46
  Tool slotting = t;
  slotting.stepover = 10;  // the whole diameter: a slot
  EXPECT_NEAR(slotting.feed_engagement_deg(), 180.0, 1e-12);
  Tool stated = t;
  stated.feed_engagement = 45;
  EXPECT_EQ(stated.feed_engagement_deg(), 45.0);
}

TEST(ChipThinning, ReferenceEngagementGivesTheTableFeed) {
  Tool t = roughing_tool();
  EXPECT_NEAR(feed_for_engagement(t, t.feed_engagement_deg(), 0), 1500, 1e-9);
  t.feed_engagement = 30;
  EXPECT_NEAR(feed_for_engagement(t, 30, 0), 1500, 1e-9);
}

TEST(ChipThinning, LighterCutsFeedFasterUpToTheCaps) {
  Tool t = roughing_tool();
  t.feed_engagement = 90;  // the feed holds for a half-width cut: fz is the chip
  // sin(90) / sin(phi): a 30-degree cut makes half the chip, so twice the feed keeps it.
  EXPECT_NEAR(feed_for_engagement(t, 30, 0), 3000, 1e-9);
  EXPECT_NEAR(feed_for_engagement(t, 60, 0), 1500 / std::sin(60 * kRad), 1e-9);
  // At and beyond 90 degrees the chip is fz: the same feed, a slot too.
  EXPECT_NEAR(feed_for_engagement(t, 120, 0), 1500, 1e-9);
  EXPECT_NEAR(feed_for_engagement(t, 180, 0), 1500, 1e-9);
  // Lighter still: three times the table's feed at most, and the machine's largest feed.
  EXPECT_NEAR(feed_for_engagement(t, 10, 0), kMaxFeedFactor * 1500, 1e-9);
  EXPECT_NEAR(feed_for_engagement(t, 30, 2000), 2000, 1e-9);
  // Below a few degrees the cutter is in air: the cap.
  EXPECT_NEAR(feed_for_engagement(t, 0, 0), 4500, 1e-9);
  EXPECT_NEAR(feed_for_engagement(t, 1, 4000), 4000, 1e-9);
  // The feed falls monotonically as the engagement rises to 90.
  double before = INFINITY;
  for (double phi = 2; phi <= 90; phi += 1) {
    const double f = feed_for_engagement(t, phi, 0);
    EXPECT_LE(f, before);
    before = f;
  }
}

TEST(ChipThinning, SlottingSlowsATableFeedGivenForASideCut) {
  const Tool t = roughing_tool();  // 1500 at 78.46 degrees
  EXPECT_NEAR(feed_for_engagement(t, 180, 0), 1500 * std::sin(std::acos(0.2)), 1e-9);  // 1469.7
  EXPECT_LT(feed_for_engagement(t, 180, 0), 1500);
}

TEST(ChipThinning, BadValuesAreRefusedByName) {
  const Tool t = roughing_tool();
  EXPECT_NE(error_of([&] { feed_for_engagement(t, -1, 0); }).find("engagement: must lie in [0, 180]"),
            std::string::npos);
  EXPECT_NE(error_of([&] { feed_for_engagement(t, NAN, 0); }).find("engagement"), std::string::npos);
  EXPECT_NE(error_of([&] { feed_for_engagement(t, 181, 0); }).find("engagement"), std::string::npos);
  EXPECT_NE(error_of([&] { feed_for_engagement(t, 90, -5); }).find("max_feed"), std::string::npos);
}

TEST(ChipThinning, ToolTableReadsFeedEngagement) {
  const std::string row =
      "tools:\n  - {id: 1, type: flat, diameter: 10, flute_length: 30, shank_diameter: 10, spindle_rpm: 10000,\n"
      "     feed: 1500, plunge_feed: 400, stepover: 4, stepdown: 2";
  const ToolTable stated = parse_tool_table(row + ", feed_engagement: 60}\n", "tools.yaml");
  EXPECT_EQ(stated.tools[0].feed_engagement_deg(), 60.0);
  const ToolTable left_out = parse_tool_table(row + "}\n", "tools.yaml");
  EXPECT_TRUE(std::isnan(left_out.tools[0].feed_engagement));
  EXPECT_NEAR(left_out.tools[0].feed_engagement_deg(), 78.463, 1e-3);
  EXPECT_NE(error_of([&] {
              parse_tool_table(row + ", feed_engagement: 0}\n", "tools.yaml");
            }).find("tools[0].feed_engagement: must lie in (0, 180] degrees"),
            std::string::npos);
  EXPECT_NE(error_of([&] { parse_tool_table(row + ", feed_engagement: 200}\n", "tools.yaml"); })
                .find("feed_engagement"),
            std::string::npos);
}
