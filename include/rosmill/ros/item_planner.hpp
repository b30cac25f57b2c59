// One plan item (setup, strategy, tool, parameters, source) planned by rosmill::plan(request) and turned into the
// messages the planner node publishes: the job in the setup's frame (published on tf) and its statistics. The
// settings are the node's parameters, read and checked once at start-up.
#pragma once
#include <ros/node_handle.h>
#include <sensor_msgs/PointCloud2.h>

#include <Eigen/Geometry>
#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include "rosmill/PlanItem.h"
#include "rosmill/PlanStatistics.h"
#include "rosmill/ToolpathJob.h"
#include "rosmill/cloud/cloud_input.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/trajectory_limits.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/planner/presets.hpp"
#include "rosmill/ros/plan_inputs.hpp"
#include "rosmill/ros/setup_frames.hpp"

namespace rosmill::edge {

struct PlannerSettings {
  std::string frame_id;        // the workpiece frame
  std::string strategy;        // for a mesh when an item names none
  std::string cloud_strategy;  // for a cloud when an item names none
  std::string setup;           // for a plan on input
  int tool_id = 2;             // when an item names none
  ToolTable tools;
  PlanParams defaults;
  PresetTable presets;
  CloudInputOptions cloud_input;
  std::string option_prefix;   // the node's private namespace: where cloud options are named in errors
  // The machine's trajectory planner (parameter machine: its machine file) that times the plans; without: the
  // time at the feeds alone.
  gcode::TrajectoryLimits trajectory;
  std::optional<gcode::MachineLimits> machine;  // the same file: a five-axis plan is timed for its TCP control
};

// The settings from the node's private parameters; an Error names a bad one.
PlannerSettings planner_settings(const ::ros::NodeHandle& pnh);

struct PlanOutcome {
  Job job;
  SetupFrame setup;
  msg::ToolpathJob job_msg;  // in the setup's frame
  msg::PlanStatistics statistics;
};

// A Plan request and a PlanToolpath item have the same fields.
template <typename Msg>
msg::PlanItem plan_item_of(const Msg& m) {
  msg::PlanItem item;
  item.setup = m.setup;
  item.direction = m.direction;
  item.strategy = m.strategy;
  item.tool_id = m.tool_id;
  item.source = m.source;
  item.parameters = m.parameters;
  return item;
}

// A scan as the planner takes it: read from the message (`to_workpiece` brings it into the workpiece frame), then
// prepared by the same input step as `rosmill plan` with the node's cloud options. An Error says what is wrong.
PointCloud prepared_cloud(const sensor_msgs::PointCloud2& msg, const Eigen::Isometry3d& to_workpiece,
                          const PlannerSettings& settings);

// The progress of a plan outside the action: it stops at shutdown, after `seconds`, and when `wanted` turns false
// (a plan on input superseded by a newer input). Copies share one state, so the caller learns which it was.
class PlanDeadline {
 public:
  PlanDeadline(double seconds, std::function<bool()> wanted = {});
  PlanProgress progress() const;
  bool timed_out() const { return *timed_out_; }
  // The reason a plan stopped at the limit gives, pointing to the action.
  std::string over_limit() const;

 private:
  double seconds_;
  std::chrono::steady_clock::time_point deadline_;
  std::function<bool()> wanted_;
  std::shared_ptr<std::atomic<bool>> timed_out_ = std::make_shared<std::atomic<bool>>(false);
};

class ItemPlanner {
 public:
  explicit ItemPlanner(PlannerSettings settings) : settings_(std::move(settings)) {}
  // Plans `item` on the input it names; throws Error with the reason; `progress` may cancel.
  PlanOutcome plan(const msg::PlanItem& item, const PlanInputs& inputs, const PlanProgress& progress);
  const PlannerSettings& settings() const { return settings_; }

 private:
  PlannerSettings settings_;
  SetupFramePublisher setup_frames_;
};

}  // namespace rosmill::edge
