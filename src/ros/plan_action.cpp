#include "rosmill/ros/plan_action.hpp"

#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "rosmill/error.hpp"
#include "rosmill/ros/finish_goal.hpp"
#include "rosmill/ros/markers.hpp"
#include "rosmill/ros/plan_goal.hpp"

namespace rosmill::edge {

ToolpathPublisher::ToolpathPublisher(::ros::NodeHandle& nh, std::string frame_id) : frame_id_(std::move(frame_id)) {
  job_pub_ = nh.advertise<msg::ToolpathJob>("toolpath", 1, true);
  marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("toolpath_markers", 1, true);
}

void ToolpathPublisher::publish(const PlanOutcome& out) {
  job_pub_.publish(out.job_msg);
  std_msgs::Header header = out.job_msg.header;
  header.frame_id = frame_id_;  // the markers are drawn back in the workpiece frame
  marker_pub_.publish(toolpath_markers(out.job, out.setup, header));
  ROS_INFO("toolpath_planner: %u toolpaths, %u moves for setup %s in %.3f s", out.statistics.toolpaths,
           out.statistics.moves, out.setup.name.c_str(), out.statistics.planning_time);
}

PlanActionServer::PlanActionServer(::ros::NodeHandle& nh, ItemPlanner& planner, const PlanInputs& inputs,
                                   ToolpathPublisher& out)
    : planner_(planner),
      inputs_(inputs),
      out_(out),
      server_(nh, "plan_toolpath", [this](const PlanToolpathGoalConstPtr& goal) { on_goal(goal); }, false) {
  server_.start();
}

void PlanActionServer::on_goal(const PlanToolpathGoalConstPtr& goal) {
  PlanGoalHooks hooks;
  hooks.cancel_requested = [this] { return server_.isPreemptRequested(); };
  hooks.feedback = [this](const PlanToolpathFeedback& fb) { server_.publishFeedback(fb); };
  hooks.plan_item = [&](size_t i, const PlanProgress& progress) {
    PlanOutcome out = planner_.plan(goal->items[i], inputs_, progress);
    if (server_.isPreemptRequested()) throw Error("plan", "cancelled");
    if (!goal->preview) out_.publish(out);
    msg::PlanItemResult r;
    r.job = std::move(out.job_msg);
    r.statistics = out.statistics;
    return r;
  };
  bool cancelled = false;
  const PlanToolpathResult result = run_plan_goal(*goal, hooks, cancelled);
  finish_goal(server_, result, cancelled, result.success);
}

}  // namespace rosmill::edge
