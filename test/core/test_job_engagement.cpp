// Engagement in jobs: every operation's radial engagement measured against the stock before it, in the report and
// its JSON; a roughing operation's feeds set from it by radial chip thinning, so that its program and the time
// estimate follow the cut (the box cube job: the zigzag's first line runs half in the stock, 90 degrees).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "cli_run.hpp"
#include "job_test_options.hpp"
#include "rosmill/cutter/chip_thinning.hpp"
#include "rosmill/job/run_job.hpp"
#include "rosmill/verify/engagement.hpp"

using namespace rosmill::core;
using namespace rosmill::core::job;

namespace {

const std::string kJob = std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/box_cube.yaml";

// Every operation's toolpaths as the job ran them.
JobReport run_keeping_toolpaths(JobOptions o, std::vector<Job>& toolpaths) {
  o.operation_done = [&](const OperationView& v) { toolpaths.push_back(v.toolpaths); };
  return run_job(read_job(kJob), o);
}

// Minutes the feed moves of the toolpaths take at their feeds.
double feed_minutes(const Job& job) {
  double minutes = 0;
  for (const Toolpath& tp : job) {
    Vec3 at = tp.start;
    for (const ToolpathPass& pass : tp.passes)
      for (const Move& mv : pass.moves) {
        if (mv.type != MoveType::Rapid) minutes += (mv.to - at).norm() / mv.feed;
        at = mv.to;
      }
  }
  return minutes;
}

// The feeds of the moves that travel in XY at the cutting feed (not plunges or ramps).
std::multiset<double> cutting_feeds(const Job& job) {
  std::multiset<double> feeds;
  for (const Toolpath& tp : job) {
    Vec3 at = tp.start;
    for (const ToolpathPass& pass : tp.passes)
      for (const Move& mv : pass.moves) {
        if (mv.type == MoveType::Feed && (mv.to - at).head<2>().norm() >= 1e-6) feeds.insert(mv.feed);
        at = mv.to;
      }
  }
  return feeds;
}

}  // namespace

TEST(JobEngagement, RoughingReportsItsEngagementAndFeedsFollowIt) {
  std::vector<Job> toolpaths;
  const JobOptions options = job_test::options();
  const JobReport r = run_keeping_toolpaths(options, toolpaths);
  ASSERT_EQ(r.operations.size(), 3u);
  ASSERT_EQ(toolpaths.size(), 3u);
  const OperationReport& rough = r.operations[0];
  ASSERT_TRUE(rough.roughing);
  ASSERT_TRUE(rough.engagement_measured);
  const verify::EngagementReport& e = rough.engagement;
  // The zigzag starts with the cutter's axis on the stock's edge: half of it in the material, 90 degrees, the most
  // it takes (its later lines step over 3.9 mm of 10, 77 degrees, and its side passes run on the stock's edge).
  EXPECT_NEAR(e.max_deg, 90.0, verify::kEngagementToleranceDeg);
  EXPECT_LE(e.p95_deg, e.max_deg);
  EXPECT_GE(e.p95_deg, 77.0 - verify::kEngagementToleranceDeg);
  double histogram = 0;
  for (double mm : e.histogram_mm) histogram += mm;
  EXPECT_NEAR(histogram, e.radial_mm, 1e-6 * e.radial_mm);
  // The measurement's finer grid removes what the in-process stock removes, to its coarser cells.
  EXPECT_NEAR(e.removed_mm3, rough.removed_mm3, 0.01 * rough.removed_mm3);
  // Its rate is timed by the feeds the program got.
  // (the simulator's moves hold their feed as a float: a relative 1e-7)
  EXPECT_NEAR(e.feed_minutes, feed_minutes(toolpaths[0]), 1e-7 * e.feed_minutes);
  EXPECT_NEAR(e.mrr_mm3_per_min, e.removed_mm3 / e.feed_minutes, 1e-9 * e.mrr_mm3_per_min);
  // The tool table's 10 mm end mill: 1500 mm/min at its 4 mm stepover (78.46 degrees). In the 90-degree cuts the
  // chip is fz: 1500 sin(78.46) = 1469.7; in air the machine's largest feed, 1828 (under three times 1500).
  const Tool& tool = job_test::package_tools().get(1);
  const double at_90 = feed_for_engagement(tool, 90, options.checks.machine->max_feed);
  EXPECT_NEAR(at_90, 1500 * std::sin(std::acos(0.2)), 1e-9);
  const std::multiset<double> feeds = cutting_feeds(toolpaths[0]);
  EXPECT_EQ(rough.feeds_from_engagement, feeds.size());
  EXPECT_GT(feeds.count(at_90), 0u);
  EXPECT_GT(feeds.count(1828.0), 0u);
  EXPECT_GE(*feeds.begin(), at_90 - 1e-9);
  EXPECT_LE(*feeds.rbegin(), 1828.0);
  // Finishing is measured too and keeps the table's feed.
  const OperationReport& finish = r.operations[1];
  EXPECT_FALSE(finish.roughing);
  EXPECT_TRUE(finish.engagement_measured);
  EXPECT_EQ(finish.feeds_from_engagement, 0u);
  for (double f : cutting_feeds(toolpaths[1])) EXPECT_EQ(f, 1200.0);
  // At the table's feeds the time estimate differs by what the feeds changed.
  JobOptions table = options;
  table.feeds_from_engagement = false;
  std::vector<Job> at_table;
  const JobReport t = run_keeping_toolpaths(table, at_table);
  EXPECT_EQ(t.operations[0].feeds_from_engagement, 0u);
  EXPECT_EQ(*cutting_feeds(at_table[0]).begin(), 1500.0);
  EXPECT_NEAR(t.operations[0].engagement.max_deg, e.max_deg, 1e-9);
  EXPECT_NE(t.operations[0].time_s, rough.time_s);
  EXPECT_NEAR(t.operations[0].engagement.feed_minutes, feed_minutes(at_table[0]), 1e-9 * e.feed_minutes);
}

TEST(JobEngagement, JsonCarriesEachOperationsEngagement) {
  const CliRun run = run_rosmill_in(::testing::TempDir(), "job '" + kJob + "' --json");
  ASSERT_EQ(run.status, 0) << run.out;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  ASSERT_EQ(j["operations"].size(), 3u);
  const nlohmann::json& rough = j["operations"][0];
  EXPECT_TRUE(rough["roughing"].get<bool>());
  EXPECT_NEAR(rough["engagement"]["max_deg"].get<double>(), 90.0, verify::kEngagementToleranceDeg);
  EXPECT_GT(rough["engagement"]["p95_deg"].get<double>(), 70.0);
  EXPECT_GT(rough["engagement"]["mrr_mm3_per_min"].get<double>(), 0.0);
  EXPECT_EQ(rough["engagement"]["histogram"].size(), 18u);
  EXPECT_GT(rough["feeds_from_engagement"].get<int>(), 0);
  EXPECT_EQ(j["operations"][1]["feeds_from_engagement"].get<int>(), 0);
  const CliRun text = run_rosmill_in(::testing::TempDir(), "job '" + kJob + "'");
  EXPECT_NE(text.out.find("engagement max 90.0 deg"), std::string::npos) << text.out;
  const CliRun table = run_rosmill_in(::testing::TempDir(), "job '" + kJob + "' --json --table-feeds");
  ASSERT_EQ(table.status, 0) << table.out;
  EXPECT_EQ(nlohmann::json::parse(table.out)["operations"][0]["feeds_from_engagement"].get<int>(), 0);
}
