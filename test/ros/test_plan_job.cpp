// rostest: the plan_job action of toolpath_planner (see plan_job.test).
#include <actionlib/client/simple_action_client.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <ros/ros.h>
#include <shape_msgs/Mesh.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <vector>

#include "rosmill/PlanJobAction.h"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/gcode/post.hpp"
#include "rostest_support.hpp"

using namespace rosmill;
using namespace rosmill::edge;
using Client = actionlib::SimpleActionClient<PlanJobAction>;
using rosmill::rostest::Latest;

namespace {

const std::string kJobs = std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/";

class PlanJob : public testing::Test {
 protected:
  static void SetUpTestSuite() { ASSERT_TRUE(ros::service::waitForService("plan", ros::Duration(20.0))); }
  // Sends `goal` and waits for its end (planning a job takes a few seconds; generous for a loaded machine).
  PlanJobResultConstPtr run(Client& client, const PlanJobGoal& goal) {
    client.sendGoal(goal);
    EXPECT_TRUE(client.waitForResult(ros::Duration(100.0)));
    return client.getResult();
  }
  void expect_alive() {
    EXPECT_TRUE(ros::service::waitForService("plan", ros::Duration(2.0))) << "toolpath_planner died";
  }
  ros::NodeHandle nh;
};

std::string yaml_job(const std::string& part, const std::string& operations) {
  return "part: " + part + "\nresolution: 0.5\nstock: {box: {margin: 5}}\noperations:\n" + operations;
}

// The example job through the action: the same operations as the file, figures in SI units and as the CLI's JSON,
// feedback that ends each operation with "done", the stock coloured per vertex, the toolpaths per operation, and
// nothing cut below the design.
TEST_F(PlanJob, ExampleJobRunsWithFeedbackAndMarkers) {
  Latest<visualization_msgs::MarkerArray> stock(nh, "stock_markers"), paths(nh, "job_markers");
  // What the feedback callback touches outlives the client: the client's own thread may deliver a feedback message
  // after the result (another topic), until the client is destroyed and joins that thread.
  std::mutex m;
  std::set<std::string> done;
  Client client("plan_job", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(10.0)));
  PlanJobGoal goal;
  goal.job_file = kJobs + "box_cube.yaml";
  client.sendGoal(goal, Client::SimpleDoneCallback(), Client::SimpleActiveCallback(),
                  [&](const PlanJobFeedbackConstPtr& fb) {
                    std::lock_guard<std::mutex> lock(m);
                    EXPECT_EQ(fb->operations, 3u);
                    EXPECT_GE(fb->progress, 0.0f);
                    EXPECT_LE(fb->progress, 1.0f);
                    if (fb->stage == "done") done.insert(fb->name);
                  });
  ASSERT_TRUE(client.waitForResult(ros::Duration(100.0)));
  ASSERT_EQ(client.getState(), actionlib::SimpleClientGoalState::SUCCEEDED) << client.getResult()->message;
  const PlanJobResult& r = *client.getResult();
  ASSERT_EQ(r.operations.size(), 3u);
  EXPECT_EQ(r.operations[0].name, "rough");
  EXPECT_EQ(r.operations[1].name, "finish");
  EXPECT_EQ(r.operations[2].name, "walls");
  EXPECT_FALSE(r.cancelled);
  {
    std::lock_guard<std::mutex> lock(m);
    EXPECT_EQ(done, (std::set<std::string>{"rough", "finish", "walls"}));
  }
  // Every face it was to finish (the top and the four walls) is within its limit.
  EXPECT_EQ(r.faces_to_finish, 5u);
  EXPECT_EQ(r.unfinished_faces, 0u);
  const nlohmann::json json = nlohmann::json::parse(r.report_json);
  ASSERT_EQ(json["operations"].size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    const PlanJobResult::_operations_type::value_type& op = r.operations[k];
    EXPECT_GT(op.removed_volume, 0.0);
    EXPECT_NEAR(op.removed_volume, json["operations"][k]["removed_mm3"].get<double>() * 1e-9, 1e-12);
    EXPECT_NEAR(op.cutting_length, json["operations"][k]["cutting_mm"].get<double>() * 1e-3, 1e-9);
    EXPECT_GE(op.air_cut_share, 0.0);
    EXPECT_LE(op.air_cut_share, 1.0);
    EXPECT_GT(op.time, 0.0);
    EXPECT_TRUE(op.program.empty());  // no output_dir
  }
  // One program for the one setup, every operation's toolpaths in it, in the workpiece frame (+Z).
  ASSERT_EQ(r.programs.size(), 1u);
  EXPECT_EQ(r.programs[0].header.frame_id, "workpiece");
  EXPECT_GE(r.programs[0].toolpaths.size(), 3u);
  EXPECT_TRUE(r.programs[0].rapids_checked_by_stock);
  EXPECT_GT(r.stock_volume, r.left_volume);
  EXPECT_GE(r.min_left, -1e-6);  // never below the design (1 micrometre)
  EXPECT_LT(r.max_left, 0.005);  // the finish leaves at most a few tenths on the cube's faces

  const auto s = stock.wait(10.0);
  ASSERT_TRUE(s);
  bool mesh = false;
  double stock_max_x = -1e300;
  std::vector<visualization_msgs::Marker> legend;
  for (const auto& marker : s->markers) {
    if (marker.ns == "stock") {
      mesh = true;
      EXPECT_EQ(marker.type, visualization_msgs::Marker::TRIANGLE_LIST);
      EXPECT_GT(marker.points.size(), 100u);
      EXPECT_EQ(marker.colors.size(), marker.points.size());
      EXPECT_EQ(marker.header.frame_id, "workpiece");
      for (const auto& q : marker.points) stock_max_x = std::max(stock_max_x, q.x);
    }
    if (marker.ns == "legend") legend.push_back(marker);
  }
  EXPECT_TRUE(mesh);
  ASSERT_EQ(legend.size(), 5u);
  // Beside the stock, never over it: rviz centres a text on its position, and a character is at most 0.6 of the
  // text's height wide, so each line's left end is 5 mm or more clear of the stock's +x side.
  for (const auto& line : legend)
    EXPECT_GE(line.pose.position.x - 0.3 * line.scale.z * double(line.text.size()), stock_max_x + 0.005) << line.text;
  const auto p = paths.wait(10.0);
  ASSERT_TRUE(p);
  std::set<std::string> operations;
  for (const auto& marker : p->markers)
    if (!marker.ns.empty()) operations.insert(marker.ns.substr(0, marker.ns.find('/')));
  // Each operation's toolpaths, then the part's faces by what the job left on them.
  EXPECT_EQ(operations, (std::set<std::string>{"1_rough", "2_finish", "3_walls", "surface"}));
}

// A job given as text on the mesh the planner received: the box stock is the received part's bounds grown by the
// margin, and the programs are written into output_dir, checked against the machine.
TEST_F(PlanJob, TextJobOnTheReceivedMeshWritesCheckedPrograms) {
  const Mesh cone = make_primitive("cone");
  ros::Publisher pub = nh.advertise<shape_msgs::Mesh>("/mesh", 1, true);
  rosmill::rostest::InputCount inputs(nh, "toolpath_planner: input");
  const size_t before = inputs.now();
  pub.publish(to_mesh_msg(cone));
  ASSERT_TRUE(inputs.wait_beyond(before));
  Client client("plan_job", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(10.0)));
  char folder[] = "/tmp/rosmill-plan-job-XXXXXX";
  ASSERT_NE(mkdtemp(folder), nullptr);
  PlanJobGoal goal;
  goal.job_yaml = yaml_job("primitive:cube", "  - {name: rough, strategy: rough, tool: flat:10@1, stepover: 4, "
                                              "stepdown: 3, allowance: 0.5}\n");
  goal.part_source = "mesh";
  goal.output_dir = folder;
  const auto r = run(client, goal);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->success) << r->message;
  const Box3& b = cone.bbox;
  const Vec3 size = b.max - b.min;
  const double box_mm3 = (size.x() + 10) * (size.y() + 10) * (size.z() + 5);
  EXPECT_NEAR(r->stock_volume * 1e9, box_mm3, 0.03 * box_mm3);  // within the 0.5 mm cells' rounding
  ASSERT_EQ(r->operations.size(), 1u);
  EXPECT_TRUE(std::filesystem::is_regular_file(r->operations[0].program)) << r->operations[0].program;
  EXPECT_EQ(std::filesystem::path(r->operations[0].program).parent_path(), std::filesystem::path(folder));
  // The part sits where the launch's table -> workpiece frame puts it (40, -30, -10 mm, turned 0.2 rad): the
  // program sets G54 there before its first move.
  std::string g54;
  for (const std::string& l : gcode::read_program_lines(r->operations[0].program))
    if (l.rfind("G10 L2 P1", 0) == 0) g54 = l;
  EXPECT_EQ(g54, "G10 L2 P1 X40 Y-30 Z-10 R11.4592");
  std::filesystem::remove_all(folder);
}

// A job whose setups are chosen (setups: auto) and held in a vise: the cube held on its bottom takes five setups,
// each in the result with its frame on tf (the part turned onto its tool axis, the origin at the stock's top
// centre), its own work offset (G54..G58) in its program message, its fixture among the job's markers with the
// part's faces coloured by setup, and the setup sheet beside the programs.
TEST_F(PlanJob, ChosenSetupsInAViseAreOnTfAndInTheResult) {
  Latest<visualization_msgs::MarkerArray> paths(nh, "job_markers");
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  Client client("plan_job", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(10.0)));
  char folder[] = "/tmp/rosmill-plan-job-setups-XXXXXX";
  ASSERT_NE(mkdtemp(folder), nullptr);
  PlanJobGoal goal;
  goal.job_yaml = "part: primitive:cube\nstock: {box: {margin: 5}}\nsetups: auto\nheld_face: -Z\n"
                  "auto: {tool: 2}\nfixture: {vise: {jaw_width: 100, jaw_height: 25, grip: 5, clamp: y}}\n"
                  "operations:\n  - {name: rough, strategy: rough, tool: 1, stepover: 4, stepdown: 5, allowance: 0.5}\n";
  goal.output_dir = folder;
  const auto r = run(client, goal);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->success) << r->message;
  ASSERT_EQ(r->setups.size(), 5u);
  EXPECT_NEAR(r->unreachable_area, 3600e-6, 1e-9);  // the bottom the cube is held by
  ASSERT_EQ(r->programs.size(), 5u);
  for (size_t k = 0; k < 5; ++k) {
    const msg::JobSetup& s = r->setups[k];
    EXPECT_EQ(s.frame_id, "workpiece_setup" + std::to_string(k + 1));
    EXPECT_EQ(s.work_offset, "G5" + std::to_string(4 + k));
    EXPECT_TRUE(s.work_offset_set);
    EXPECT_EQ(s.datum, "top-centre");
    EXPECT_NE(s.fixture.find("vise"), std::string::npos) << s.fixture;
    EXPECT_EQ(r->programs[k].header.frame_id, s.frame_id);
    EXPECT_EQ(r->programs[k].work_offset, k + 1);
    EXPECT_TRUE(std::filesystem::is_regular_file(s.program)) << s.program;
    // The setup's frame: its tool axis is its +Z, and its origin (the datum) is on the stock's top.
    ASSERT_TRUE(buffer.canTransform("workpiece", s.frame_id, ros::Time(0), ros::Duration(5.0))) << s.frame_id;
    const Eigen::Isometry3d pose = tf2::transformToEigen(buffer.lookupTransform("workpiece", s.frame_id, ros::Time(0)));
    const Vec3 axis = pose.linear() * Vec3::UnitZ();
    EXPECT_NEAR((axis - from_direction_msg(s.tool_axis)).norm(), 0.0, 1e-9) << s.name;
    EXPECT_NEAR((pose.translation() - Vec3(s.datum_point.x, s.datum_point.y, s.datum_point.z)).norm(), 0.0, 1e-9);
  }
  EXPECT_TRUE(std::filesystem::is_regular_file(std::string(folder) + "/setup_sheet.html"));
  const auto p = paths.wait(10.0);
  ASSERT_TRUE(p);
  // Each setup's fixture twice: a faint fill, through which the part and its toolpaths show, and its boxes' edges,
  // twelve a box (two points each) at the fill's corners (twelve triangles a box, three points each).
  size_t fills = 0, edges = 0;
  std::map<std::string, const visualization_msgs::Marker*> fill_of;
  bool by_setup = false, by_verdict = false;
  for (const auto& marker : p->markers) {
    if (marker.ns.rfind("fixture/", 0) == 0 && marker.type == visualization_msgs::Marker::TRIANGLE_LIST) {
      ++fills;
      EXPECT_LE(marker.color.a, 0.35f) << marker.ns;
      EXPECT_GT(marker.color.a, 0.0f) << marker.ns;
      fill_of[marker.ns] = &marker;
    }
    by_setup = by_setup || marker.ns == "setups";
    // After the job: the part's faces by what it left on them (a roughing finishes none: every face grey).
    by_verdict = by_verdict || (marker.ns == "surface" && !marker.points.empty());
  }
  for (const auto& marker : p->markers) {
    if (marker.ns.rfind("fixture/", 0) != 0 || marker.type != visualization_msgs::Marker::LINE_LIST) continue;
    ++edges;
    ASSERT_TRUE(fill_of.count(marker.ns)) << marker.ns;
    const auto& fill = fill_of[marker.ns]->points;
    EXPECT_EQ(marker.points.size() * 36, fill.size() * 24) << marker.ns;
    EXPECT_GT(marker.color.a, fill_of[marker.ns]->color.a) << marker.ns;
    for (const auto& q : marker.points)
      EXPECT_TRUE(std::any_of(fill.begin(), fill.end(), [&](const geometry_msgs::Point& c) {
        return std::hypot(c.x - q.x, c.y - q.y, c.z - q.z) < 1e-9;
      })) << marker.ns << ": an edge's end at no corner of the fill";
  }
  EXPECT_EQ(fills, 5u);
  EXPECT_EQ(edges, 5u);
  EXPECT_TRUE(by_setup);
  EXPECT_TRUE(by_verdict);
  std::filesystem::remove_all(folder);
}

// Bad goals are aborted with their reason; the node stays up.
TEST_F(PlanJob, BadGoalsAreRefusedWithTheirReason) {
  Client client("plan_job", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(10.0)));
  const std::string op = "  - {name: rough, strategy: rough, tool: flat:10@1}\n";
  const std::vector<std::pair<PlanJobGoal, std::string>> cases = [&] {
    std::vector<std::pair<PlanJobGoal, std::string>> c(5);
    c[0].second = "names no job";
    c[1].first.job_file = "/nonexistent/job.yaml";
    c[1].second = "/nonexistent/job.yaml";
    c[2].first.job_yaml = yaml_job("primitive:cube", "  - {name: rough, strategy: rough, tool: flat:10@1, stepover: -4}\n");
    c[2].second = "stepover";
    c[3].first.job_yaml = yaml_job("primitive:cube", op);
    c[3].first.part_source = "cloud";
    c[3].second = "part_source";
    c[4].first.job_yaml = yaml_job("primitive:cube", op);
    c[4].first.output_dir = "relative/folder";
    c[4].second = "absolute";
    return c;
  }();
  for (const auto& [goal, expected] : cases) {
    const auto r = run(client, goal);
    ASSERT_TRUE(r);
    EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::ABORTED) << expected;
    EXPECT_FALSE(r->success);
    EXPECT_NE(r->message.find(expected), std::string::npos) << r->message;
  }
  expect_alive();
}

// Cancelled once the first operation is done: the goal ends PREEMPTED with the finished operations, not all.
TEST_F(PlanJob, CancelKeepsTheFinishedOperations) {
  std::atomic<bool> cancel_sent{false};  // before the client, which calls back until it is destroyed
  Client client("plan_job", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(10.0)));
  std::string ops;
  for (int k = 0; k < 20; ++k)
    ops += "  - {name: pass" + std::to_string(k) + ", strategy: raster, tool: ball:6@2, stepover: 1}\n";
  PlanJobGoal goal;
  goal.job_yaml = yaml_job("primitive:dome", ops);
  client.sendGoal(goal, Client::SimpleDoneCallback(), Client::SimpleActiveCallback(),
                  [&](const PlanJobFeedbackConstPtr& fb) {
                    if (fb->stage == "done" && !cancel_sent.exchange(true)) client.cancelGoal();
                  });
  ASSERT_TRUE(client.waitForResult(ros::Duration(100.0)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::PREEMPTED);
  const auto r = client.getResult();
  EXPECT_TRUE(r->cancelled);
  EXPECT_GE(r->operations.size(), 1u);
  EXPECT_LT(r->operations.size(), 20u);
  expect_alive();
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_plan_job");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
