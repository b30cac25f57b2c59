// rostest node for test/ros/scan_bags.test: recorded scans played into the toolpath planner. Bad clouds (no points,
// no transform) are refused with their reason in the Plan reply; good ones give toolpaths that stay above every
// point the scanner saw.
#include <cmath>

#include "gouge_check.hpp"
#include "rosmill/Plan.h"
#include "rosmill/ToolpathJob.h"
#include "rosmill/io/cloud_io.hpp"
#include "rostest_support.hpp"

using namespace rosmill;
using namespace rosmill::edge;
using rosmill::rostest::Latest;
using rosmill::rostest::call_service;
using rosmill::rostest::node_answers;
using rosmill::rostest::param;
using rosmill::rostest::play_bag;

namespace {

constexpr double kGougeTolerance = 0.02;  // mm

Plan plan_cloud(double stepdown_m = 0.0) {
  Plan srv;
  srv.request.setup = "+Z";
  srv.request.source = "cloud";
  srv.request.parameters.stepdown = stepdown_m;
  srv.request.preview = true;
  EXPECT_TRUE(call_service("plan", srv)) << "the plan service is gone";
  return srv;
}

// Plan replies until the message holds `text` (the planner handles the cloud after the bag ends).
Plan plan_until(const std::string& text, double timeout_s) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  Plan srv = plan_cloud();
  while (srv.response.message.find(text) == std::string::npos && ros::WallTime::now() < end) {
    ros::WallDuration(0.1).sleep();
    srv = plan_cloud();
  }
  return srv;
}

// The seed dome as dome_scan.bag holds it, in the workpiece frame (mm): a 2 mm grid on the hemisphere r 50.
PointCloud dome_points() {
  PointCloud c;
  for (int i = -25; i <= 25; ++i)
    for (int j = -25; j <= 25; ++j) {
      const double x = 2.0 * i, y = 2.0 * j;
      if (x * x + y * y > 2500.0) continue;
      c.points.emplace_back(x, y, std::sqrt(std::max(2500.0 - x * x - y * y, 0.0)));
    }
  c.recompute_bbox();
  return c;
}

void expect_above_the_scan(const msg::Toolpath& tp, const PointCloud& scan, double step, const char* what) {
  const rostest::Gouge g = rostest::cloud_gouge(scan, tp, step);
  EXPECT_LE(g.depth, kGougeTolerance) << what << ": the cutter reaches " << g.depth << " mm into the scan at "
                                      << g.at.transpose();
  EXPECT_GT(g.samples, 100u);
}

// Every cutter location over the scan's box (grown by the stock margin and the radius) and not below its lowest point.
void expect_within_reach(const msg::Toolpath& tp, const PointCloud& scan) {
  const double reach = 5.0 + edge::to_mm(tp.tool.diameter) / 2 + 1e-6;
  for (const auto& pass : tp.passes)
    for (const auto& move : pass.moves) {
      const Vec3 p = edge::from_point_msg(move.position);
      EXPECT_TRUE(p.x() >= scan.bbox.min.x() - reach && p.x() <= scan.bbox.max.x() + reach &&
                  p.y() >= scan.bbox.min.y() - reach && p.y() <= scan.bbox.max.y() + reach)
          << p.transpose() << " is off the scan";
      EXPECT_GE(p.z(), scan.bbox.min.z() - 1e-6) << p.transpose();
    }
}

class ScanBags : public testing::Test {
 protected:
  static void SetUpTestSuite() { ASSERT_TRUE(ros::service::waitForService("plan", ros::Duration(20.0))); }
  ros::NodeHandle nh;
};

TEST_F(ScanBags, NothingYet) {
  Plan srv = plan_cloud();
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("no cloud has been received"), std::string::npos) << srv.response.message;
}

TEST_F(ScanBags, EmptyCloudIsRefused) {
  ASSERT_EQ(play_bag(param("bags") + "/empty_cloud.bag"), 0);
  Plan srv = plan_until("rejected", 10.0);
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("has no finite points"), std::string::npos) << srv.response.message;
  EXPECT_TRUE(node_answers("/toolpath_planner"));
}

TEST_F(ScanBags, CloudInAFrameWithoutTransformIsRefused) {
  const ros::WallTime t0 = ros::WallTime::now();
  ASSERT_EQ(play_bag(param("bags") + "/lost_frame.bag"), 0);
  Plan srv = plan_until("nowhere", 10.0);
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("cloud in frame 'nowhere'"), std::string::npos) << srv.response.message;
  EXPECT_NE(srv.response.message.find("no transform to 'workpiece' came within 1"), std::string::npos)
      << srv.response.message;
  EXPECT_LT((ros::WallTime::now() - t0).toSec(), 10.0) << "the wait for the transform is not bounded";
  EXPECT_TRUE(node_answers("/toolpath_planner"));
}

// The dome seen by a scanner 0.3 m above it: after tf2 it sits on z = 0 again, and the roughing toolpath
// published for it stays above every scanned point.
TEST_F(ScanBags, DomeScanGivesAToolpathAboveTheDome) {
  Latest<msg::ToolpathJob> job(nh, "toolpath");
  ASSERT_EQ(play_bag(param("bags") + "/dome_scan.bag"), 0);
  auto j = job.wait(30.0);
  ASSERT_TRUE(j) << "no toolpath for the dome scan";
  ASSERT_EQ(j->toolpaths.size(), 1u);
  const msg::Toolpath& tp = j->toolpaths[0];
  EXPECT_EQ(tp.strategy, "cloud-rough");
  EXPECT_EQ(tp.tool.cutter_type, msg::Tool::FLAT_END);
  EXPECT_NEAR(tp.tool.diameter, 0.010, 1e-12);
  EXPECT_EQ(j->header.frame_id, "workpiece");
  size_t moves = 0;
  for (const auto& pass : tp.passes) moves += pass.moves.size();
  EXPECT_GT(moves, 100u);
  const PointCloud dome = dome_points();
  EXPECT_NEAR(edge::to_mm(tp.safe_z), 50.0 + 5.0, 1.0);  // the top of the dome plus planner/safe_clearance
  expect_within_reach(tp, dome);
  expect_above_the_scan(tp, dome, 0.5, "dome");
  // The check itself: 2 mm lower, the cutter is in the dome (roughing leaves 0.5 mm and its steps).
  msg::Toolpath lowered = tp;
  for (auto& pass : lowered.passes)
    for (auto& move : pass.moves) move.position.z -= 0.002;
  EXPECT_GT(rostest::cloud_gouge(dome, lowered, 0.5).depth, 1.0);
  // The roughing goes down the flanks: the lowest cut is near the dome's foot, not only over its top.
  double lowest = 1e9;
  for (const auto& pass : tp.passes)
    for (const auto& move : pass.moves)
      if (move.move_type == msg::ToolpathMove::FEED) lowest = std::min(lowest, edge::to_mm(move.position.z));
  EXPECT_LT(lowest, 5.0);

  Plan srv = plan_cloud();
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_EQ(srv.response.statistics.moves, moves);
}

TEST_F(ScanBags, BunnyScanGivesAToolpathAboveTheBunny) {
  Latest<msg::ToolpathJob> job(nh, "toolpath");
  ASSERT_TRUE(job.wait(5.0));
  const size_t before = job.count();
  ASSERT_EQ(play_bag(param("bags") + "/bunny_scan.bag"), 0);
  auto j = job.wait(30.0, before);
  ASSERT_TRUE(j) << "no toolpath for the bunny scan";
  const PointCloud bunny = read_cloud(param("data") + "/pcl_bunny.pcd");
  ASSERT_EQ(bunny.points.size(), 397u);
  expect_within_reach(j->toolpaths.at(0), bunny);
  expect_above_the_scan(j->toolpaths.at(0), bunny, 0.5, "bunny");
}

// A real part scanned in a robot cell, 0.8 m from the cell's origin: tf2 brings it onto the workpiece origin.
TEST_F(ScanBags, RealPartScanInTheCellFrame) {
  Latest<msg::ToolpathJob> job(nh, "toolpath");
  ASSERT_TRUE(job.wait(5.0));
  const size_t before = job.count();
  ASSERT_EQ(play_bag(param("bags") + "/part_scan.bag"), 0);
  ASSERT_TRUE(job.wait(30.0, before)) << "no toolpath for the part scan";
  // The scan in the workpiece frame: the cell's points moved by the static transform of the launch file.
  PointCloud part = read_cloud(param("data") + "/snp_part_scan.ply");
  for (Vec3& p : part.points) p += Vec3(-797.7, -10.0, -87.0);
  part.recompute_bbox();
  Plan srv = plan_cloud(0.020);  // 20 mm levels keep the check quick; the published job used the tool's 2 mm
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  const msg::Toolpath& tp = srv.response.job.toolpaths.at(0);
  EXPECT_NEAR(srv.response.statistics.bounds_max.z, edge::to_metres(part.bbox.max.z() + 5.0), 0.002);
  expect_within_reach(tp, part);
  expect_above_the_scan(tp, part, 2.0, "part scan");
  EXPECT_TRUE(node_answers("/toolpath_planner"));
}

}  // namespace

int main(int argc, char** argv) { return rosmill::rostest::run_all(argc, argv, "test_scan_bags"); }
