// rostest node for test/ros/planner_services.test: the toolpath planner answers bad input with errors and keeps
// running; a mesh plans differently for the +Z and the -X setups; the PlanToolpath action reports and cancels.
#include <actionlib/client/simple_action_client.h>
#include <sensor_msgs/PointCloud2.h>
#include <shape_msgs/Mesh.h>
#include <visualization_msgs/MarkerArray.h>

#include "rostest_support.hpp"
#include "rosmill/Plan.h"
#include "rosmill/PlanToolpathAction.h"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/ros/convert.hpp"

using namespace rosmill;
using rosmill::rostest::Latest;

namespace {

bool strategy_known(const std::string& name) {
  for (const auto& s : strategies())
    if (s.name == name) return true;
  return false;
}

Plan call_plan(const std::string& setup, const std::string& strategy = "", int tool_id = 0,
               const std::string& source = "") {
  Plan srv;
  srv.request.setup = setup;
  srv.request.strategy = strategy;
  srv.request.tool_id = tool_id;
  srv.request.source = source;
  EXPECT_TRUE(ros::service::call("plan", srv)) << "the plan service is gone";
  return srv;
}

void expect_alive() {
  EXPECT_TRUE(ros::service::waitForService("plan", ros::Duration(2.0))) << "toolpath_planner died";
}

class PlannerServices : public testing::Test {
 protected:
  static void SetUpTestSuite() { ASSERT_TRUE(ros::service::waitForService("plan", ros::Duration(20.0))); }
  ros::NodeHandle nh;
};

// Order matters: gtest runs tests in the order written, and the first one sees the planner without input.
TEST_F(PlannerServices, PlanWithoutInputIsAnError) {
  Plan srv = call_plan("+Z", "", 0, "");
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("no input yet"), std::string::npos) << srv.response.message;
  expect_alive();
}

TEST_F(PlannerServices, EmptyCloudIsRejected) {
  ros::Publisher pub = nh.advertise<sensor_msgs::PointCloud2>("/scan/points", 1, true);
  PointCloud empty;
  pub.publish(edge::to_cloud_msg(empty, "workpiece"));
  ros::WallDuration(1.0).sleep();
  Plan srv = call_plan("+Z", "", 0, "cloud");
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("no cloud"), std::string::npos) << srv.response.message;
  expect_alive();
}

TEST_F(PlannerServices, CloudWithoutTransformIsRejected) {
  ros::Publisher pub = nh.advertise<sensor_msgs::PointCloud2>("/scan/points", 1, true);
  PointCloud cloud;
  for (int i = 0; i < 100; ++i) cloud.points.emplace_back(i, 2.0 * i, 10.0);
  cloud.recompute_bbox();
  pub.publish(edge::to_cloud_msg(cloud, "nowhere"));
  ros::WallDuration(2.0).sleep();  // the planner waits tf_timeout (1 s) for the transform
  Plan srv = call_plan("+Z", "", 0, "cloud");
  EXPECT_FALSE(srv.response.success);
  expect_alive();
}

TEST_F(PlannerServices, InvalidRequestsGetReasons) {
  ros::Publisher pub = nh.advertise<shape_msgs::Mesh>("/mesh", 1, true);
  pub.publish(edge::to_mesh_msg(make_primitive("dome")));
  ros::WallDuration(1.0).sleep();

  Plan bad_setup = call_plan("+Q", "", 0, "mesh");
  EXPECT_FALSE(bad_setup.response.success);
  EXPECT_NE(bad_setup.response.message.find("setup"), std::string::npos) << bad_setup.response.message;

  Plan zero_direction = call_plan("", "", 0, "mesh");  // no name and a zero direction
  EXPECT_FALSE(zero_direction.response.success);
  EXPECT_NE(zero_direction.response.message.find("direction"), std::string::npos);

  Plan bad_tool = call_plan("+Z", "", 99, "mesh");
  EXPECT_FALSE(bad_tool.response.success);
  EXPECT_NE(bad_tool.response.message.find("no tool 99"), std::string::npos) << bad_tool.response.message;

  Plan bad_strategy = call_plan("+Z", "no-such-strategy", 0, "mesh");
  EXPECT_FALSE(bad_strategy.response.success);
  EXPECT_NE(bad_strategy.response.message.find("unknown strategy"), std::string::npos);

  Plan bad_source = call_plan("+Z", "", 0, "moon");
  EXPECT_FALSE(bad_source.response.success);
  EXPECT_NE(bad_source.response.message.find("source"), std::string::npos);

  Plan negative;
  negative.request.setup = "+Z";
  negative.request.source = "mesh";
  negative.request.parameters.stepover = -0.001;
  ASSERT_TRUE(ros::service::call("plan", negative));
  EXPECT_FALSE(negative.response.success);
  EXPECT_NE(negative.response.message.find("stepover"), std::string::npos) << negative.response.message;

  Plan too_wide;
  too_wide.request.setup = "+Z";
  too_wide.request.source = "mesh";
  too_wide.request.parameters.stepover = 0.050;  // 50 mm with a 6 mm tool
  ASSERT_TRUE(ros::service::call("plan", too_wide));
  EXPECT_FALSE(too_wide.response.success);
  expect_alive();
}

TEST_F(PlannerServices, ActionAbortsAnInvalidGoalWithItsReason) {
  actionlib::SimpleActionClient<PlanToolpathAction> client("plan_toolpath", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(10.0)));
  PlanToolpathGoal goal;
  goal.setup = "sideways";
  goal.source = "mesh";
  client.sendGoal(goal);
  ASSERT_TRUE(client.waitForResult(ros::Duration(10.0)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::ABORTED);
  EXPECT_FALSE(client.getResult()->success);
  EXPECT_NE(client.getResult()->message.find("sideways"), std::string::npos);
  expect_alive();
}

// +Z and -X machine different faces of the cube: the toolpaths differ, and each stays in the part's reach.
TEST_F(PlannerServices, PlusZAndMinusXSetupsGiveDifferentToolpaths) {
  if (!strategy_known("raster")) GTEST_SKIP() << "the raster strategy has not landed in the core yet";
  ros::Publisher pub = nh.advertise<shape_msgs::Mesh>("/mesh", 1, true);
  const Mesh cone = make_primitive("cone");
  pub.publish(edge::to_mesh_msg(cone));
  ros::WallDuration(1.0).sleep();
  Plan z = call_plan("+Z", "raster", 2, "mesh");
  Plan x = call_plan("-X", "raster", 2, "mesh");
  ASSERT_TRUE(z.response.success) << z.response.message;
  ASSERT_TRUE(x.response.success) << x.response.message;
  ASSERT_FALSE(z.response.job.toolpaths.empty());
  ASSERT_FALSE(x.response.job.toolpaths.empty());
  EXPECT_EQ(z.response.job.toolpaths[0].setup, "+Z");
  EXPECT_EQ(x.response.job.toolpaths[0].setup, "-X");
  EXPECT_NEAR(x.response.job.toolpaths[0].tool_axis.x, -1.0, 1e-9);
  // The cone seen from the side (-X) is a triangle 50 mm wide and 60 mm tall; from above a 50 mm disc: the toolpath
  // bounds in the setup frame differ.
  const auto& bz = z.response.statistics;
  const auto& bx = x.response.statistics;
  EXPECT_GT(std::abs((bz.bounds_max.y - bz.bounds_min.y) - (bx.bounds_max.y - bx.bounds_min.y)) +
                std::abs(bz.moves - double(bx.moves)),
            0.0);
  EXPECT_NE(bz.moves, bx.moves);
}

}  // namespace

int main(int argc, char** argv) { return rosmill::rostest::run_all(argc, argv, "test_planner_services"); }
