// The planner's outputs and its plan_toolpath action. ToolpathPublisher publishes a plan: the job (latched on
// `toolpath`) and its view (`toolpath_markers`, drawn in the workpiece frame). PlanActionServer serves
// `plan_toolpath`: several items planned by the ItemPlanner on the node's inputs, each published unless the goal is
// a preview, with feedback and cancel (run_plan_goal).
#pragma once
#include <actionlib/server/simple_action_server.h>
#include <ros/node_handle.h>

#include "rosmill/PlanToolpathAction.h"
#include "rosmill/ros/item_planner.hpp"
#include "rosmill/ros/plan_inputs.hpp"

namespace rosmill::edge {

class ToolpathPublisher {
 public:
  ToolpathPublisher(::ros::NodeHandle& nh, std::string frame_id);
  void publish(const PlanOutcome& out);

 private:
  std::string frame_id_;
  ::ros::Publisher job_pub_, marker_pub_;
};

class PlanActionServer {
 public:
  PlanActionServer(::ros::NodeHandle& nh, ItemPlanner& planner, const PlanInputs& inputs, ToolpathPublisher& out);

 private:
  void on_goal(const PlanToolpathGoalConstPtr& goal);

  ItemPlanner& planner_;
  const PlanInputs& inputs_;
  ToolpathPublisher& out_;
  actionlib::SimpleActionServer<PlanToolpathAction> server_;
};

}  // namespace rosmill::edge
