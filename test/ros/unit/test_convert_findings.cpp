// The ROS edge's conversions (src/ros/convert.cpp) as fuzz_ros_convert found them: a toolpath message whose
// heights, start, feeds or tool diameter are not finite numbers was accepted and would have become a program.
// Each is refused naming the field. A plain gtest: no ROS master.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "error_of.hpp"
#include "rosmill/ros/convert.hpp"

namespace {

using namespace rosmill;
using core::SetupFrame;
using core::Vec3;

edge::msg::Toolpath valid_toolpath() {
  edge::msg::Toolpath m;
  m.setup_rotation.w = 1;
  m.tool.cutter_type = edge::msg::Tool::FLAT_END;
  m.tool.diameter = 0.006;
  m.safe_z = 0.01;
  m.clearance_z = 0.005;
  m.passes.resize(1);
  m.passes[0].moves.resize(2);
  m.passes[0].moves[0].move_type = edge::msg::ToolpathMove::RAPID;
  m.passes[0].moves[1].move_type = edge::msg::ToolpathMove::FEED;
  m.passes[0].moves[1].position.x = 0.01;
  m.passes[0].moves[1].feed_rate = 0.02;  // m/s: 1200 mm/min
  return m;
}

TEST(ConvertFindings, ToolpathNumbersThatAreNotFiniteAreRefused) {
  const core::Toolpath good = edge::from_toolpath_msg(valid_toolpath());
  EXPECT_DOUBLE_EQ(good.safe_z, 10.0);
  EXPECT_DOUBLE_EQ(good.passes[0].moves[1].feed, 1200.0);

  const std::pair<void (*)(edge::msg::Toolpath&), std::string> cases[] = {
      {[](edge::msg::Toolpath& m) { m.safe_z = std::nan(""); }, "safe_z and clearance_z must be finite"},
      {[](edge::msg::Toolpath& m) { m.clearance_z = -std::numeric_limits<double>::infinity(); }, "clearance_z"},
      {[](edge::msg::Toolpath& m) { m.start.y = std::nan(""); }, "start is not finite"},
      {[](edge::msg::Toolpath& m) { m.passes[0].moves[0].feed_rate = std::nan(""); }, "pass 0 move 0: feed_rate"},
      {[](edge::msg::Toolpath& m) { m.passes[0].moves[1].feed_rate = std::numeric_limits<double>::infinity(); },
       "pass 0 move 1: feed_rate must be finite"},
      {[](edge::msg::Toolpath& m) { m.tool.diameter = std::numeric_limits<double>::infinity(); },
       "diameter must be positive and finite"},
  };
  for (const auto& [spoil, reason] : cases) {
    edge::msg::Toolpath m = valid_toolpath();
    spoil(m);
    EXPECT_NE(error_of([&] { edge::from_toolpath_msg(m, "toolpath"); }).find(reason), std::string::npos) << reason;
  }
}

// A five-axis pass's tool axes cross the message and back; an axis count that is not the moves' or an axis that is
// not a finite unit vector is refused naming the pass and the axis.
TEST(ConvertFindings, ToolAxesCrossTheMessageAndBadOnesAreRefused) {
  core::Toolpath tp = edge::from_toolpath_msg(valid_toolpath());
  tp.passes[0].axes = {Vec3::UnitZ(), Vec3(0.6, 0, 0.8)};
  const edge::msg::Toolpath m = edge::to_toolpath_msg(tp, SetupFrame{});
  ASSERT_EQ(m.passes[0].axes.size(), 2u);
  const core::Toolpath back = edge::from_toolpath_msg(m);
  ASSERT_TRUE(back.multi_axis());
  EXPECT_LT((back.passes[0].axes[1] - Vec3(0.6, 0, 0.8)).norm(), 1e-15);
  EXPECT_FALSE(edge::from_toolpath_msg(valid_toolpath()).multi_axis());  // none: a 3-axis pass

  const std::pair<void (*)(edge::msg::Toolpath&), std::string> cases[] = {
      {[](edge::msg::Toolpath& m) { m.passes[0].axes.pop_back(); }, "pass 0 axes: must hold one tool axis per move"},
      {[](edge::msg::Toolpath& m) { m.passes[0].axes[1].z = 2.0; }, "pass 0 axes[1]: a tool axis must be a finite"},
      {[](edge::msg::Toolpath& m) { m.passes[0].axes[0].x = std::nan(""); }, "pass 0 axes[0]"},
      {[](edge::msg::Toolpath& m) { m.passes[0].axes[0] = geometry_msgs::Vector3(); }, "pass 0 axes[0]"},
  };
  for (const auto& [spoil, reason] : cases) {
    edge::msg::Toolpath bad = m;
    spoil(bad);
    EXPECT_NE(error_of([&] { edge::from_toolpath_msg(bad, "toolpath"); }).find(reason), std::string::npos) << reason;
  }
}

}  // namespace
