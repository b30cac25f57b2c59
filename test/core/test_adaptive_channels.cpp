// Adaptive clearing in channels and gaps (plan/adaptive.hpp): a channel 1.2 or 1.4 diameters wide between an
// island and a pocket's wall is cleared; a gap narrower than the tool is listed in the report (PlanReport::left)
// with its reason. The material left is measured by the verifier's stock simulation of the written toolpath, code
// the planner does not share.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "job_test_options.hpp"
#include "rosmill/cutter/chip_thinning.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/job/job_spec.hpp"
#include "rosmill/job/run_job.hpp"
#include "rosmill/plan/adaptive.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/stock/program.hpp"
#include "rosmill/verify/verify.hpp"

using namespace rosmill::core;

namespace {

// test/data/parts/channels_pocket.scad: the pocket [10, 70] x [10, 50], floor at z 8, in a block 80 x 60 x 20.
const Box3 kBlock = Box3::between(Vec3(0, 0, 0), Vec3(80, 60, 20));

struct Planned {
  Mesh part;
  Job job;
  PlanReport report;
};

// A 5 mm end mill at FreeCAD's 20 % step-over (53 degrees), step-down 3, the stock the part's bounds.
const Planned& channels_pocket() {
  static const Planned planned = [] {
    Planned p;
    p.part = read_stl(ROSMILL_TEST_DATA "/parts/channels_pocket.stl");
    PlanParams params;
    params.tool = default_tool(Cutter{CutterType::FlatEnd, 5, 0});
    params.tool.id = 1;
    params.stepover = 1;
    params.stepdown = 3;
    params.allowance = 0.2;
    params.tolerance = 0.01;
    params.stock_margin = 0;
    const MeshSurface surface(p.part);
    p.job = adaptive_on(surface, params, AdaptiveOptions{}, {}, &p.report);
    return p;
  }();
  return planned;
}

// The largest material left over the design in the rectangle (the verifier's grid of 0.25 mm).
double left_in(const verify::VerifyResult& v, double x0, double x1, double y0, double y1) {
  const stock::GridSpec& g = v.grid.grid;
  double worst = -INFINITY;
  for (int j = g.first_y(y0); j <= g.last_y(y1); ++j)
    for (int i = g.first_x(x0); i <= g.last_x(x1); ++i)
      worst = std::max(worst, double(v.grid.deviation[g.index(i, j)]));
  return worst;
}

}  // namespace

// The channel (6 mm for a 5 mm end mill) and a 7 mm one are cleared to the allowance at the engagement
// limit (the planner's own measure, stated in the report; entries excluded).
TEST(AdaptiveChannels, ChannelsWiderThanTheToolAreClearedToTheAllowance) {
  const Planned& a = channels_pocket();
  EXPECT_NEAR(a.report.engagement_limit_deg, std::acos(1 - 1.0 / 2.5) * 180 / M_PI, 1e-9);
  EXPECT_LE(a.report.max_engagement_deg, a.report.engagement_limit_deg);
  verify::StockSpec spec;
  spec.kind = verify::StockSpec::Kind::Box;
  spec.box = kBlock;
  verify::VerifyOptions o;
  o.resolution = 0.25;
  const verify::VerifyResult v = verify::verify_program(a.part, stock::program_from_job(a.job), spec, o);
  EXPECT_LE(v.report.max_gouge_mm, 0.0);
  // The 6 mm channel between the round island at (30, 39) and the +Y wall, away from the island's sides by a
  // cell and from the wall by the allowance and a cell.
  EXPECT_LE(left_in(v, 28, 32, 44.5, 49.5), 0.2 + 0.01);
  // The 7 mm channel between the island at (59, 34) and the +X wall.
  EXPECT_LE(left_in(v, 63.5, 69.5, 32, 36), 0.2 + 0.01);
  // The floor between the islands.
  EXPECT_LE(left_in(v, 15, 40, 15, 30), 0.2 + 0.01);
  // The 6 mm channel leaves the cutter's centre 0.6 mm (6 - 2 x (2.5 + 0.2)), under the turn radius's 1 mm: no pass
  // fits, and it is cut as a slot, stated with its engagement and its feed (chip thinning, no slower than a full
  // slot's, no faster than the limit's). About the island's width at each of the 4 levels under the top, both ways.
  EXPECT_GT(a.report.slot_length_mm, 10.0);
  EXPECT_LE(a.report.slot_length_mm, 4 * 2 * 20.0);
  EXPECT_GT(a.report.slot_max_engagement_deg, a.report.engagement_limit_deg);
  EXPECT_LE(a.report.slot_max_engagement_deg, 180.0);
  const Tool tool = default_tool(Cutter{CutterType::FlatEnd, 5, 0});
  EXPECT_GE(a.report.slot_feed, feed_for_engagement(tool, 180, 0) - 1e-9);
  EXPECT_LE(a.report.slot_feed, feed_for_engagement(tool, a.report.engagement_limit_deg, 0) + 1e-9);
}

// The 4 mm gap under the square island [42, 56] x [14, 26] is listed at every level, with its reason, at about its
// area (4 x 14 mm and the two bays at its mouths the cutter cannot round); the channels are not listed.
TEST(AdaptiveChannels, AGapNarrowerThanTheToolIsListedWithItsReason) {
  const Planned& a = channels_pocket();
  size_t gap_levels = 0;
  for (const UnclearedPatch& l : a.report.uncleared) {
    SCOPED_TRACE(testing::Message() << "z " << l.z << " at " << l.x << " " << l.y << ": " << l.area_mm2);
    if (l.z < 9) {  // the floor's level: nothing left in the channels
      EXPECT_FALSE(l.x > 25 && l.x < 35 && l.y > 44);  // the 6 mm channel
      EXPECT_FALSE(l.x > 63 && l.y > 30 && l.y < 38);  // the 7 mm channel
    }
    if (std::abs(l.x - 49) < 1 && std::abs(l.y - 12) < 1) {
      ++gap_levels;
      EXPECT_EQ(l.reason, UnclearedReason::kNarrowerThanTheTool);
      EXPECT_GE(l.area_mm2, 4 * 14 * 0.9);
      EXPECT_LE(l.area_mm2, 4 * 14 + 2 * 2.5 * 2.5);
    }
  }
  EXPECT_EQ(gap_levels, 4u);  // every level under the block's top: 17, 14, 11 and the floor's 8.2
  EXPECT_STREQ(uncleared_reason_text(UnclearedReason::kNarrowerThanTheTool), "narrower than the tool");
}

// Between passes the cutter goes round the islands through the air the level cleared instead of lifting: 134 lifts
// on this pocket before such links, at most 30 now (15 when written); the way keeps out of the part, which the
// verifier's gouge check of the whole program (above) covers.
TEST(AdaptiveChannels, LinksGoThroughClearedAirRatherThanLifting) {
  const Planned& a = channels_pocket();
  EXPECT_GT(a.report.air_links, 0u);
  EXPECT_LE(a.report.lifts, 30u);
}

// The job says what adaptive clearing could not clear, as `plan` does: the operation's report keeps the strategy's
// patches and slots, and the job's JSON lists them with their reasons.
TEST(AdaptiveChannels, TheJobListsWhatItCouldNotClear) {
  const job::JobSpec spec = job::parse_job(
      "part: " ROSMILL_TEST_DATA "/parts/channels_pocket.stl\nstock: {box: {margin: 0}}\noperations:\n"
      "  - {name: clear, strategy: adaptive, tool: flat:5@1, stepover: 1, stepdown: 5, allowance: 0.2}\n",
      "channels.yaml", ROSMILL_SOURCE_DIR);
  const job::JobReport r = job::run_job(spec, job_test::options());
  const job::OperationReport& op = r.operations.at(0);
  size_t gap = 0, listed = 0;
  for (const PlanReport& p : op.plan_reports)
    for (const UnclearedPatch& l : p.uncleared) {
      ++listed;
      gap += std::abs(l.x - 49) < 1 && std::abs(l.y - 12) < 1 && l.reason == UnclearedReason::kNarrowerThanTheTool;
    }
  EXPECT_GE(gap, 3u);  // the 4 mm gap at every level under the top
  const nlohmann::json j = job::to_json(r)["operations"][0];
  ASSERT_TRUE(j.contains("uncleared"));
  EXPECT_EQ(j["uncleared"].size(), listed);
  EXPECT_EQ(j["uncleared"][0]["reason"].get<std::string>().empty(), false);
  EXPECT_LE(r.gouge_mm, 0.0);
}
