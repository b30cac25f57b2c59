// rostest node for test/ros/planner_services.test: the toolpath planner answers bad input with errors and keeps
// running; a mesh plans differently for the +Z and the -X setups; the PlanToolpath action reports and cancels.
#include <actionlib/client/simple_action_client.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <sensor_msgs/PointCloud2.h>
#include <shape_msgs/Mesh.h>
#include <visualization_msgs/MarkerArray.h>

#include "rostest_support.hpp"
#include "rosmill/Plan.h"
#include "rosmill/PlanToolpathAction.h"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/planner/strategy_table.hpp"
#include "rosmill/ros/convert.hpp"

#include <atomic>

using namespace rosmill;
using namespace rosmill::edge;
using rosmill::rostest::Latest;
using rosmill::rostest::call_service;
using rosmill::rostest::node_pid;
using rosmill::rostest::peak_rss_mb;

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
  EXPECT_TRUE(call_service("plan", srv)) << "the plan service is gone";
  return srv;
}

// Asks for a plan of `source` until its answer contains `text` (the planner takes an input asynchronously).
Plan plan_until(const std::string& source, const std::string& text, double timeout_s = 20.0) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  Plan srv = call_plan("+Z", "", 0, source);
  while (srv.response.message.find(text) == std::string::npos && ros::WallTime::now() < end) {
    ros::WallDuration(0.05).sleep();
    srv = call_plan("+Z", "", 0, source);
  }
  return srv;
}

// Publishes an input on `pub` and waits until the planner has taken it (its input count on /diagnostics).
template <typename M>
void publish_and_wait(ros::Publisher& pub, const M& message, const std::string& node = "toolpath_planner") {
  ros::NodeHandle nh;
  rosmill::rostest::InputCount inputs(nh, node + ": input");
  const size_t before = inputs.now();
  pub.publish(message);
  ASSERT_TRUE(inputs.wait_beyond(before)) << node << " did not take the input";
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
  publish_and_wait(pub, edge::to_cloud_msg(empty, "workpiece"));
  Plan srv = call_plan("+Z", "", 0, "cloud");
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("no finite points"), std::string::npos) << srv.response.message;
  expect_alive();
}

TEST_F(PlannerServices, CloudWithoutTransformIsRejected) {
  ros::Publisher pub = nh.advertise<sensor_msgs::PointCloud2>("/scan/points", 1, true);
  PointCloud cloud;
  for (int i = 0; i < 100; ++i) cloud.points.emplace_back(i, 2.0 * i, 10.0);
  cloud.recompute_bbox();
  publish_and_wait(pub, edge::to_cloud_msg(cloud, "nowhere"));  // after tf_timeout (1 s) for the transform
  Plan srv = call_plan("+Z", "", 0, "cloud");
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("no transform to 'workpiece'"), std::string::npos) << srv.response.message;
  expect_alive();
}

sensor_msgs::PointCloud2 xyz_cloud(uint32_t width, uint32_t point_step, size_t bytes) {
  sensor_msgs::PointCloud2 m;
  m.header.frame_id = "workpiece";
  m.height = 1;
  m.width = width;
  m.point_step = point_step;
  m.row_step = width * point_step;
  for (const char* name : {"x", "y", "z"}) {
    sensor_msgs::PointField f;
    f.name = name;
    f.offset = uint32_t(4 * m.fields.size());
    f.datatype = sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    m.fields.push_back(f);
  }
  m.data.assign(bytes, 0);
  return m;
}

// Layouts whose reads would fall outside the message (each crashed the planner once) are rejected with the reason,
// and the planner stays up; the rejection is on /diagnostics too.
TEST_F(PlannerServices, HostileCloudLayoutsAreRejected) {
  ros::Publisher pub = nh.advertise<sensor_msgs::PointCloud2>("/scan/points", 1, true);
  Latest<diagnostic_msgs::DiagnosticArray> diagnostics(nh, "/diagnostics");
  pub.publish(xyz_cloud(1, 0, 0));
  Plan srv = plan_until("cloud", "point_step 0");
  EXPECT_NE(srv.response.message.find("point_step 0"), std::string::npos) << srv.response.message;
  expect_alive();

  sensor_msgs::PointCloud2 far_field = xyz_cloud(1, 12, 12);
  far_field.fields[2].offset = 1000000;
  pub.publish(far_field);
  srv = plan_until("cloud", "offset 1000000");
  EXPECT_NE(srv.response.message.find("field z at offset 1000000 (4 bytes) lies beyond point_step 12"),
            std::string::npos) << srv.response.message;
  expect_alive();

  sensor_msgs::PointCloud2 short_rows = xyz_cloud(4, 12, 48);
  short_rows.height = 2;  // two rows announced, one held
  pub.publish(short_rows);
  srv = plan_until("cloud", "bytes;");
  EXPECT_NE(srv.response.message.find("holds 48 bytes; 2 row(s) of 4 points of 12 bytes need 96"), std::string::npos)
      << srv.response.message;

  sensor_msgs::PointCloud2 big_endian = xyz_cloud(4, 12, 48);
  big_endian.is_bigendian = true;
  pub.publish(big_endian);
  srv = plan_until("cloud", "big-endian");
  EXPECT_NE(srv.response.message.find("big-endian"), std::string::npos) << srv.response.message;
  expect_alive();

  bool reported = false;
  for (int i = 0; i < 200 && !reported; ++i) {
    if (auto d = diagnostics.wait(5.0))
      for (const auto& status : d->status)
        reported |= status.name.find("toolpath_planner") != std::string::npos &&
                    status.message.find("big-endian") != std::string::npos &&
                    status.level == diagnostic_msgs::DiagnosticStatus::WARN;
    if (!reported) ros::WallDuration(0.05).sleep();
  }
  EXPECT_TRUE(reported) << "no WARN diagnostic of toolpath_planner naming the rejected cloud";
}

// The plan service and planning on input stop at service_time_limit and point to the action (the `limited`
// planner of planner_services.test has a limit of 0.05 s).
TEST_F(PlannerServices, ServicePlansStopAtTheTimeLimit) {
  ros::Publisher pub = nh.advertise<shape_msgs::Mesh>("/limited/mesh", 1, true);
  pub.publish(edge::to_mesh_msg(make_primitive("dome")));
  ASSERT_TRUE(ros::service::waitForService("/limited/plan", ros::Duration(20.0)));
  Plan srv;
  srv.request.setup = "+Z";
  srv.request.source = "mesh";
  srv.request.tool_id = 3;
  srv.request.parameters.stepover = 0.00005;  // minutes of work at 0.05 mm over the dome
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  do {
    ASSERT_TRUE(call_service("/limited/plan", srv));
  } while (srv.response.message.find("no mesh") != std::string::npos && ros::WallTime::now() < end);
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("plan_toolpath action"), std::string::npos) << srv.response.message;
  EXPECT_TRUE(ros::service::waitForService("/limited/plan", ros::Duration(2.0)));
}

Plan plan_with(const msg::PlanParameters& parameters, const std::string& strategy = "raster") {
  Plan srv;
  srv.request.setup = "+Z";
  srv.request.source = "mesh";
  srv.request.strategy = strategy;
  srv.request.parameters = parameters;
  EXPECT_TRUE(call_service("plan", srv)) << "the plan service is gone";
  return srv;
}

// Work beyond the bounds is refused before anything of its size is allocated, with the estimate: a mesh a
// thousand kilometres across (planned on arrival and on request), a micrometre stepover, step-down or tolerance;
// and values that make no sense are refused naming the field. The planner answers each at once and its memory
// stays bounded.
TEST_F(PlannerServices, WorkBeyondTheBoundsIsRefusedInBoundedMemory) {
  ros::Publisher pub = nh.advertise<shape_msgs::Mesh>("/mesh", 1, true);
  const double a = 1e9;  // mm: 1e6 m
  const Mesh huge = build_mesh({Vec3(0, 0, 0), Vec3(a, 0, 0), Vec3(0, a, 0), Vec3(0, 0, 0), Vec3(0, 0, a),
                                Vec3(a, 0, 0), Vec3(0, 0, 0), Vec3(0, a, 0), Vec3(0, 0, a), Vec3(a, 0, 0),
                                Vec3(0, 0, a), Vec3(0, a, 0)});
  ASSERT_EQ(huge.faces.size(), 4u);
  pub.publish(edge::to_mesh_msg(huge));
  Plan srv = plan_until("mesh", "would ");
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("limit"), std::string::npos) << srv.response.message;

  pub.publish(edge::to_mesh_msg(make_primitive("dome")));
  msg::PlanParameters ok;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  while (!plan_with(ok).response.success && ros::WallTime::now() < end) ros::WallDuration(0.05).sleep();
  ASSERT_TRUE(plan_with(ok).response.success);
  struct Case {
    const char* field;
    double msg::PlanParameters::*member;
    double value;
    const char* strategy;
    const char* expect;
  };
  const Case cases[] = {
      {"stepover", &msg::PlanParameters::stepover, 1e-9, "raster", "stepover"},
      {"stepdown", &msg::PlanParameters::stepdown, 1e-9, "rough", "would "},
      {"tolerance", &msg::PlanParameters::tolerance, 1e-12, "raster", "tolerance"},
      {"allowance", &msg::PlanParameters::allowance, 1.0, "raster", "allowance"},
      {"stock_margin", &msg::PlanParameters::stock_margin, 1e6, "raster", "stock_margin"},
      {"angle", &msg::PlanParameters::angle, 1e9, "raster", "angle"},
  };
  for (const Case& c : cases) {
    msg::PlanParameters p;
    p.*c.member = c.value;
    const ros::WallTime t0 = ros::WallTime::now();
    Plan bad = plan_with(p, c.strategy);
    EXPECT_FALSE(bad.response.success) << c.field;
    EXPECT_NE(bad.response.message.find(c.expect), std::string::npos) << c.field << ": " << bad.response.message;
    EXPECT_LT((ros::WallTime::now() - t0).toSec(), 10.0) << c.field << " was not refused up front";
  }
  const int pid = node_pid("/toolpath_planner");
  ASSERT_GT(pid, 0);
  EXPECT_LT(peak_rss_mb(pid), 1024.0) << "the planner's peak memory";
  expect_alive();
}

TEST_F(PlannerServices, InvalidRequestsGetReasons) {
  ros::Publisher pub = nh.advertise<shape_msgs::Mesh>("/mesh", 1, true);
  publish_and_wait(pub, edge::to_mesh_msg(make_primitive("dome")));

  Plan bad_setup = call_plan("+Q", "", 0, "mesh");
  EXPECT_FALSE(bad_setup.response.success);
  EXPECT_NE(bad_setup.response.message.find("setup"), std::string::npos) << bad_setup.response.message;

  Plan zero_direction = call_plan("", "", 0, "mesh");  // no name and a zero direction
  EXPECT_FALSE(zero_direction.response.success);
  EXPECT_NE(zero_direction.response.message.find("direction"), std::string::npos);

  Plan bad_tool = call_plan("+Z", "", 99, "mesh");
  EXPECT_FALSE(bad_tool.response.success);
  EXPECT_NE(bad_tool.response.message.find("no tool with id 99"), std::string::npos) << bad_tool.response.message;

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
  ASSERT_TRUE(call_service("plan", negative));
  EXPECT_FALSE(negative.response.success);
  EXPECT_NE(negative.response.message.find("stepover"), std::string::npos) << negative.response.message;

  Plan too_wide;
  too_wide.request.setup = "+Z";
  too_wide.request.source = "mesh";
  too_wide.request.parameters.stepover = 0.050;  // 50 mm with a 6 mm tool
  ASSERT_TRUE(call_service("plan", too_wide));
  EXPECT_FALSE(too_wide.response.success);
  expect_alive();
}

msg::PlanItem item(const std::string& setup, const std::string& strategy = "", int tool_id = 0) {
  msg::PlanItem i;
  i.setup = setup;
  i.strategy = strategy;
  i.tool_id = tool_id;
  i.source = "mesh";
  return i;
}

TEST_F(PlannerServices, ActionAbortsAnInvalidGoalWithItsReason) {
  actionlib::SimpleActionClient<PlanToolpathAction> client("plan_toolpath", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(10.0)));
  PlanToolpathGoal goal;
  goal.items.push_back(item("sideways"));
  client.sendGoal(goal);
  ASSERT_TRUE(client.waitForResult(ros::Duration(10.0)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::ABORTED);
  ASSERT_EQ(client.getResult()->results.size(), 1u);
  EXPECT_FALSE(client.getResult()->success);
  EXPECT_FALSE(client.getResult()->results[0].valid);
  EXPECT_NE(client.getResult()->results[0].message.find("sideways"), std::string::npos);

  client.sendGoal(PlanToolpathGoal());  // no items at all
  ASSERT_TRUE(client.waitForResult(ros::Duration(10.0)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::ABORTED);
  EXPECT_NE(client.getResult()->message.find("no items"), std::string::npos);
  expect_alive();
}

// Per-item validity: each item of a goal gets its own verdict and reason; with proceed_on_failure the items after a
// bad one are still planned, without it they are reported as not planned. Feedback names the item.
TEST_F(PlannerServices, ActionReportsEachItem) {
  ros::Publisher pub = nh.advertise<shape_msgs::Mesh>("/mesh", 1, true);
  publish_and_wait(pub, edge::to_mesh_msg(make_primitive("cone")));
  // What the feedback callback touches outlives the client, whose thread calls back until it is destroyed.
  std::vector<uint32_t> feedback_items;
  std::mutex m;
  actionlib::SimpleActionClient<PlanToolpathAction> client("plan_toolpath", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(10.0)));
  PlanToolpathGoal goal;
  goal.items = {item("+Z", "raster", 2), item("+Z", "raster", 42), item("-X", "raster", 2)};
  goal.proceed_on_failure = true;
  goal.preview = true;
  client.sendGoal(goal, {}, {}, [&](const PlanToolpathFeedbackConstPtr& fb) {
    std::lock_guard<std::mutex> lock(m);
    EXPECT_EQ(fb->items, 3u);
    EXPECT_GE(fb->progress, 0.0f);
    EXPECT_LE(fb->progress, 1.0f);
    feedback_items.push_back(fb->item);
  });
  ASSERT_TRUE(client.waitForResult(ros::Duration(30.0)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::ABORTED);  // not every item is valid
  auto result = client.getResult();
  ASSERT_EQ(result->results.size(), 3u);
  EXPECT_TRUE(result->results[0].valid) << result->results[0].message;
  EXPECT_FALSE(result->results[1].valid);
  EXPECT_NE(result->results[1].message.find("no tool with id 42"), std::string::npos) << result->results[1].message;
  EXPECT_TRUE(result->results[2].valid) << result->results[2].message;
  EXPECT_EQ(result->results[2].job.toolpaths.at(0).setup, "-X");
  EXPECT_GT(result->results[0].statistics.moves, 0u);
  {
    std::lock_guard<std::mutex> lock(m);
    ASSERT_FALSE(feedback_items.empty());
    EXPECT_EQ(feedback_items.front(), 0u);
    EXPECT_EQ(*std::max_element(feedback_items.begin(), feedback_items.end()), 2u);
  }

  goal.proceed_on_failure = false;
  client.sendGoal(goal);
  ASSERT_TRUE(client.waitForResult(ros::Duration(30.0)));
  result = client.getResult();
  ASSERT_EQ(result->results.size(), 3u);
  EXPECT_TRUE(result->results[0].valid);
  EXPECT_FALSE(result->results[1].valid);
  EXPECT_FALSE(result->results[2].valid);
  EXPECT_NE(result->results[2].message.find("not planned"), std::string::npos) << result->results[2].message;
  expect_alive();
}

// Preemption: a cancel stops the item being planned and keeps what was finished before it.
TEST_F(PlannerServices, ActionCancelKeepsFinishedItems) {
  ros::Publisher pub = nh.advertise<shape_msgs::Mesh>("/mesh", 1, true);
  publish_and_wait(pub, edge::to_mesh_msg(make_primitive("dome")));
  std::atomic<bool> second_started{false};  // before the client, which calls back until it is destroyed
  actionlib::SimpleActionClient<PlanToolpathAction> client("plan_toolpath", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(10.0)));
  PlanToolpathGoal goal;
  goal.preview = true;
  goal.items.push_back(item("+Z", "raster", 2));
  // A long one: the 3 mm ball at a 0.05 mm stepover over the whole dome takes far longer than the test waits.
  msg::PlanItem slow = item("+Z", "raster", 3);
  slow.parameters.stepover = 0.00005;
  goal.items.push_back(slow);
  goal.items.push_back(item("-X", "raster", 2));
  client.sendGoal(goal, {}, {}, [&](const PlanToolpathFeedbackConstPtr& fb) {
    if (fb->item == 1) second_started = true;
  });
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  while (!second_started && ros::WallTime::now() < end) ros::WallDuration(0.01).sleep();
  ASSERT_TRUE(second_started) << "the second item never started";
  ros::WallDuration(0.3).sleep();
  const ros::WallTime cancel_at = ros::WallTime::now();
  client.cancelGoal();
  ASSERT_TRUE(client.waitForResult(ros::Duration(10.0)));
  EXPECT_LT((ros::WallTime::now() - cancel_at).toSec(), 5.0) << "cancel took too long";
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::PREEMPTED);
  auto result = client.getResult();
  ASSERT_EQ(result->results.size(), 3u);
  EXPECT_TRUE(result->results[0].valid);
  EXPECT_FALSE(result->results[0].job.toolpaths.empty());
  EXPECT_FALSE(result->results[1].valid);
  EXPECT_NE(result->results[1].message.find("cancelled"), std::string::npos) << result->results[1].message;
  EXPECT_FALSE(result->results[2].valid);
  expect_alive();
}

// preview answers without touching the published toolpath.
TEST_F(PlannerServices, PreviewDoesNotPublish) {
  ros::Publisher pub = nh.advertise<shape_msgs::Mesh>("/mesh", 1, true);
  publish_and_wait(pub, edge::to_mesh_msg(make_primitive("cone")));
  std::mutex m;
  std::vector<std::string> setups;  // the setup of every toolpath published from here on
  ros::Subscriber sub = nh.subscribe<msg::ToolpathJob>(
      "toolpath", 10, boost::function<void(const msg::ToolpathJob::ConstPtr&)>([&](const msg::ToolpathJob::ConstPtr& j) {
        std::lock_guard<std::mutex> lock(m);
        setups.push_back(j->toolpaths.empty() ? "" : j->toolpaths[0].setup);
      }));
  auto published_minus_x = [&] {
    std::lock_guard<std::mutex> lock(m);
    return std::count(setups.begin(), setups.end(), "-X");
  };
  Plan srv;
  srv.request.setup = "-X";
  srv.request.source = "mesh";
  srv.request.preview = true;
  ASSERT_TRUE(call_service("plan", srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  ros::WallDuration(0.5).sleep();  // a publication, if there were one, would be on its way by now
  EXPECT_EQ(published_minus_x(), 0);
  srv.request.preview = false;
  ASSERT_TRUE(call_service("plan", srv));
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  while (published_minus_x() == 0 && ros::WallTime::now() < end) ros::WallDuration(0.02).sleep();
  EXPECT_EQ(published_minus_x(), 1);
}

// +Z and -X machine different faces of the cube: the toolpaths differ, and each stays in the part's reach.
TEST_F(PlannerServices, PlusZAndMinusXSetupsGiveDifferentToolpaths) {
  if (!strategy_known("raster")) GTEST_SKIP() << "the raster strategy has not landed in the core yet";
  ros::Publisher pub = nh.advertise<shape_msgs::Mesh>("/mesh", 1, true);
  const Mesh cone = make_primitive("cone");
  publish_and_wait(pub, edge::to_mesh_msg(cone));
  Plan z = call_plan("+Z", "raster", 2, "mesh");
  Plan x = call_plan("-X", "raster", 2, "mesh");
  ASSERT_TRUE(z.response.success) << z.response.message;
  ASSERT_TRUE(x.response.success) << x.response.message;
  ASSERT_FALSE(z.response.job.toolpaths.empty());
  ASSERT_FALSE(x.response.job.toolpaths.empty());
  EXPECT_EQ(z.response.job.toolpaths[0].setup, "+Z");
  EXPECT_EQ(x.response.job.toolpaths[0].setup, "-X");
  EXPECT_NEAR(x.response.job.toolpaths[0].tool_axis.x, -1.0, 1e-9);
  // Each is stamped with the frame it is in: +Z is the workpiece frame, -X its own frame on tf, whose +Z (the tool
  // axis) is the workpiece's -X: the retract height lies on the -X side of the cone (radius 25 mm).
  EXPECT_EQ(z.response.job.header.frame_id, "workpiece");
  EXPECT_EQ(x.response.job.header.frame_id, "workpiece_setup_mx");
  EXPECT_EQ(x.response.job.toolpaths[0].header.frame_id, "workpiece_setup_mx");
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ASSERT_TRUE(buffer.canTransform("workpiece", "workpiece_setup_mx", ros::Time(0), ros::Duration(10.0)));
  const Eigen::Isometry3d t =
      tf2::transformToEigen(buffer.lookupTransform("workpiece", "workpiece_setup_mx", ros::Time(0)));
  EXPECT_TRUE((t.linear() * Vec3::UnitZ()).isApprox(Vec3(-1, 0, 0), 1e-9));
  const double clearance = x.response.job.toolpaths[0].clearance_z;
  EXPECT_LT((t * Vec3(0, 0, clearance)).x(), -0.025);
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
