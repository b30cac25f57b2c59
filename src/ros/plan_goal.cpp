#include "rosmill/ros/plan_goal.hpp"

#include <ros/ros.h>

#include "rosmill/error.hpp"

namespace rosmill::edge {
namespace {

// Feedback for item `index` of `count` at `fraction` of it, at most every 0.1 s unless `force`.
class FeedbackThrottle {
 public:
  FeedbackThrottle(const PlanGoalHooks& hooks, size_t count) : hooks_(hooks), count_(count) {}
  void operator()(size_t index, double fraction, const char* stage, bool force) {
    const ::ros::WallTime now = ::ros::WallTime::now();
    if (!force && (now - last_).toSec() < 0.1) return;
    PlanToolpathFeedback fb;
    fb.item = index;
    fb.items = count_;
    fb.stage = stage;
    fb.item_progress = float(fraction);
    fb.progress = float((index + fraction) / count_);
    hooks_.feedback(fb);
    last_ = now;
  }

 private:
  const PlanGoalHooks& hooks_;
  size_t count_;
  ::ros::WallTime last_;
};

}  // namespace

std::string plan_summary(const msg::PlanStatistics& s) {
  return "planned " + std::to_string(s.toolpaths) + " toolpath(s), " + std::to_string(s.moves) + " moves";
}

PlanToolpathResult run_plan_goal(const PlanToolpathGoal& goal, const PlanGoalHooks& hooks, bool& cancelled) {
  PlanToolpathResult result;
  const size_t n = goal.items.size();
  result.results.resize(n);
  cancelled = false;
  if (n == 0) {
    result.message = "the goal has no items";
    return result;
  }
  FeedbackThrottle feedback(hooks, n);
  size_t valid = 0;
  std::string first_failure;
  for (size_t i = 0; i < n; ++i) {
    msg::PlanItemResult& r = result.results[i];
    if (cancelled || (!first_failure.empty() && !goal.proceed_on_failure)) {
      r.message = cancelled ? "not planned: the goal was cancelled" : "not planned: " + first_failure;
      continue;
    }
    feedback(i, 0.0, "planning", true);
    const PlanProgress progress = [&, i](double fraction) {
      feedback(i, fraction, "planning", false);
      return !hooks.cancel_requested() && ::ros::ok();
    };
    try {
      if (hooks.cancel_requested()) throw Error("plan", "cancelled");
      r = hooks.plan_item(i, progress);
      feedback(i, 1.0, "planned", true);
      r.valid = true;
      r.message = plan_summary(r.statistics);
      ++valid;
    } catch (const std::exception& e) {
      r.message = e.what();
      cancelled = hooks.cancel_requested();
      if (!cancelled && first_failure.empty()) first_failure = "item " + std::to_string(i) + " failed: " + e.what();
    }
  }
  feedback(n - 1, 1.0, "done", true);
  result.success = valid == n;
  result.message = std::to_string(valid) + " of " + std::to_string(n) + " item(s) planned" +
                   (cancelled ? "; cancelled" : first_failure.empty() ? "" : "; " + first_failure);
  return result;
}

}  // namespace rosmill::edge
