// rostest node for test/ros/five_axis.test: a five-axis finish of the seed dome (r 50 mm) through the nodes. The
// toolpath message carries a tool axis at every move; the ball it places stays clear of the dome by the exact
// distance of scan/mesh_distance (no code of the planner's); rviz gets the axes as strokes; the plan is timed for
// the machine's tool-centre-point control; the bridge writes the job for that control into a folder.
#include <actionlib/client/simple_action_client.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <string>

#include "../core/five_axis_check.hpp"
#include "rosmill/Plan.h"
#include "rosmill/RunProgramAction.h"
#include "rosmill/ToolpathJob.h"
#include "rosmill/gcode/post.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/ros/convert.hpp"
#include "rostest_support.hpp"

using namespace rosmill;
using namespace rosmill::edge;
using rosmill::rostest::call_service;
using rosmill::rostest::Latest;

namespace {

constexpr double kBallRadius = 3.0;  // mm: tool 2 of config/tools.yaml, a 6 mm ball

double degrees_between(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

class FiveAxisNodes : public testing::Test {
 protected:
  static void SetUpTestSuite() { ASSERT_TRUE(ros::service::waitForService("plan", ros::Duration(20.0))); }
  ros::NodeHandle nh;
};

// The planner plans on the mesh's arrival: one five-axis toolpath whose every pass gives an axis per move.
TEST_F(FiveAxisNodes, ToolpathCarriesAToolAxisAtEveryMoveAndClearsTheDome) {
  Latest<msg::ToolpathJob> job(nh, "toolpath");
  const auto m = job.wait(90.0);
  ASSERT_TRUE(m) << "no toolpath";
  ASSERT_EQ(m->toolpaths.size(), 1u);
  const msg::Toolpath& tp = m->toolpaths[0];
  EXPECT_EQ(tp.strategy, "five-axis");
  const core::Toolpath back = from_toolpath_msg(tp);  // refuses an axis count or an axis that is not a unit
  ASSERT_TRUE(back.multi_axis());
  const Mesh dome = make_primitive("dome");  // the distance keeps a reference to it
  const five_axis_check::IndependentDistance distance(dome);
  size_t cutting = 0, tilted = 0;
  double closest = INFINITY, most_tilt = 0;
  for (const core::ToolpathPass& pass : back.passes) {
    ASSERT_EQ(pass.axes.size(), pass.moves.size()) << pass.name;
    for (size_t k = 0; k < pass.moves.size(); ++k) {
      if (pass.moves[k].type == MoveType::Rapid) continue;
      // The ball's centre: up the axis from the tip by the radius; no closer to the dome than the radius.
      const Vec3 centre = pass.moves[k].to + kBallRadius * pass.axes[k];
      const double d = distance(centre, kBallRadius + 1.0);
      closest = std::min(closest, d);
      if (d > kBallRadius + 0.05) continue;  // an approach or a retract, not on the surface
      ++cutting;
      const double tilt = degrees_between(pass.axes[k], Vec3::UnitZ());
      most_tilt = std::max(most_tilt, tilt);
      tilted += tilt > 5.0;
    }
  }
  std::cout << std::setprecision(6) << "five-axis dome: " << cutting << " cutter locations on the surface, " << tilted
            << " tilted over 5 degrees, most " << most_tilt << " degrees; closest ball centre " << closest
            << " mm from the dome (radius " << kBallRadius << ")\n";
  EXPECT_GT(cutting, 1000u);
  EXPECT_GT(tilted, cutting / 2) << "the axis follows the dome's normal";
  EXPECT_LE(most_tilt, 60.0 + 1e-6) << "the stated cone";
  EXPECT_GE(closest, kBallRadius - 0.002) << "the ball cuts into the dome";
}

// rviz: each multi-axis pass has its axes as a LINE_LIST of strokes up the axis.
TEST_F(FiveAxisNodes, MarkersDrawTheToolAxes) {
  Latest<visualization_msgs::MarkerArray> markers(nh, "toolpath_markers");
  const auto mk = markers.wait(90.0);
  ASSERT_TRUE(mk);
  size_t strokes = 0;
  for (const auto& marker : mk->markers) {
    if (marker.ns.size() < 5 || marker.ns.compare(marker.ns.size() - 5, 5, "/axes") != 0) continue;
    ASSERT_EQ(marker.type, visualization_msgs::Marker::LINE_LIST);
    ASSERT_EQ(marker.points.size() % 2, 0u);
    for (size_t k = 0; k + 1 < marker.points.size(); k += 2) {
      const Vec3 a = from_point_msg(marker.points[k]), b = from_point_msg(marker.points[k + 1]);
      EXPECT_NEAR((b - a).norm(), 12.0, 1e-6);  // twice the ball's diameter (mm)
      EXPECT_GT(b.z(), a.z() - 1e-9);           // up the axis, towards the spindle
      ++strokes;
    }
  }
  EXPECT_GT(strokes, 100u);
}

// The plan service answers with the plan's time as written for the trunnion's tool-centre-point control, and the
// bridge writes the published job for it: M428 before the cuts, A and C at the moves, inverse time, M429 at the end.
TEST_F(FiveAxisNodes, PlanIsTimedAndTheBridgeWritesItForToolCentrePointControl) {
  Plan srv;
  srv.request.setup = "+Z";
  srv.request.source = "mesh";
  ASSERT_TRUE(call_service("plan", srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_TRUE(std::isfinite(srv.response.statistics.estimated_duration));
  EXPECT_GT(srv.response.statistics.estimated_duration, 60.0);

  Latest<msg::ToolpathJob> job(nh, "toolpath");
  const auto m = job.wait(30.0);
  ASSERT_TRUE(m);
  std::string folder;
  ASSERT_TRUE(ros::param::get("~folder", folder));
  std::filesystem::create_directories(folder);
  actionlib::SimpleActionClient<RunProgramAction> client("run_program", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(20.0)));
  RunProgramGoal goal;
  goal.job = *m;
  // The dome stands on a 20 mm riser over the C axis (its base at the table's top, the ball would go below it).
  goal.job.work_offset = 1;
  goal.job.work_offset_origin.z = 0.020;
  goal.controller = "file://" + folder;
  client.sendGoal(goal);
  ASSERT_TRUE(client.waitForResult(ros::Duration(60.0)));
  const auto result = client.getResult();
  ASSERT_TRUE(result->success) << result->message;
  const std::vector<std::string> lines = gcode::read_program_lines(result->program);
  size_t on = 0, off = 0, inverse_time = 0, turning = 0;
  for (const std::string& l : lines) {
    on += l.rfind("M428", 0) == 0;
    off += l.rfind("M429", 0) == 0;
    inverse_time += l.find("G93") != std::string::npos;
    // Moves under tool-centre-point control that turn the table (motion words are modal: "X.. Y.. C.. F..").
    turning += on == 1 && l[0] != '(' && (l.find(" A") != std::string::npos || l.find(" C") != std::string::npos);
  }
  EXPECT_EQ(on, 1u);
  EXPECT_GE(off, 1u);
  EXPECT_GE(inverse_time, 1u);
  EXPECT_GT(turning, 100u);
}

}  // namespace

int main(int argc, char** argv) { return rosmill::rostest::run_all(argc, argv, "test_five_axis_nodes"); }
