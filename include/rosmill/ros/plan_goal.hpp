// One PlanToolpath goal, item by item: feedback per item and stage (at most every 0.1 s within an item), each item
// answered valid or not with its reason, the items after a failure reported as not planned unless the goal says
// to proceed, and a cancel that stops the item being planned while keeping those finished before it.
#pragma once
#include <functional>
#include <string>

#include "rosmill/PlanToolpathAction.h"
#include "rosmill/plan/plan_params.hpp"
#include "rosmill/ros/namespaces.hpp"

namespace rosmill::edge {

struct PlanGoalHooks {
  // Plans (and, unless the goal is a preview, publishes) item `index`; throws on failure. `progress` returns
  // false once the goal is cancelled.
  std::function<msg::PlanItemResult(size_t index, const PlanProgress& progress)> plan_item;
  std::function<bool()> cancel_requested;
  std::function<void(const PlanToolpathFeedback&)> feedback;
};

// "planned 2 toolpath(s), 840 moves": how a plan request and a goal item report a valid plan.
std::string plan_summary(const msg::PlanStatistics& s);

// Runs every item of `goal`; `cancelled` tells whether the goal was cancelled on the way.
PlanToolpathResult run_plan_goal(const PlanToolpathGoal& goal, const PlanGoalHooks& hooks, bool& cancelled);

}  // namespace rosmill::edge
