// One PlanJob goal in the planner node: the job read from its file or its text, run by the core's run_job with the
// node's tools and presets on the part the job names (or the mesh the node last received), feedback per operation
// (at most every 0.1 s within one), a cancel that keeps the finished operations, and after each operation what it
// did handed to `show` (rviz). The result carries the report in SI units and as the CLI's JSON (millimetres).
#pragma once
#include <actionlib/server/simple_action_server.h>
#include <ros/node_handle.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "rosmill/PlanJobAction.h"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/job/job_options.hpp"
#include "rosmill/job/run_job.hpp"
#include "rosmill/planner/presets.hpp"
#include "rosmill/ros/namespaces.hpp"
#include "rosmill/ros/setup_frames.hpp"
#include "rosmill/ros/work_offset_tf.hpp"

namespace rosmill::edge {

struct JobGoalContext {
  // The node's part of every goal's request: tools, presets, machine, no_limits, verify_rs274, dialect (the goal
  // adds its output folder, per_operation, table_feeds and part; the work offset is the one below).
  job::JobRequest request;
  std::function<std::shared_ptr<const Mesh>()> received_mesh;  // the part for part_source "mesh" (or an Error)
  std::function<bool()> cancel_requested;
  std::function<void(const PlanJobFeedback&)> feedback;
  std::function<void(const job::OperationView&)> show;
  // After the job: the part (workpiece frame) with what the job left on each of its faces.
  std::function<void(const Mesh& part, const job::SurfaceAccount&)> show_surface;
  // Publishes the frame of the job's setup `index` on tf; returns its name (job_setup_frame_id).
  std::function<std::string(const SetupFrame&, size_t index)> setup_frame;
  // Where G54 is for the written programs (G10 L2 P1 in each); none: the controller's G54 as it stands.
  std::function<std::optional<gcode::WorkOffset>()> work_offset;
};

// `cancelled` tells whether the goal was cancelled on the way.
PlanJobResult run_job_goal(const PlanJobGoal& goal, const JobGoalContext& context, bool& cancelled);

// The core's report as the action's result (m, m^3, s).
PlanJobResult to_job_result(const job::JobReport& report);

// The plan_job action of a node: its server, the `job_markers` and `stock_markers` topics (latched, workpiece
// frame), and the settings from the node's private parameters: `dialect`, `machine` (the machine file: the limits
// programs are checked against, required to write programs unless `no_limits`; its trajectory times the moves and
// its clearance over the stock is what links keep), `verify_rs274`, and those of the work offset
// (work_offset_tf.hpp).
class JobActionServer {
 public:
  // `tf` (the node's, outliving the server) gives the work offset with the work_offset_frame parameter.
  JobActionServer(::ros::NodeHandle& nh, const ::ros::NodeHandle& pnh, const std::string& frame_id,
                  const ToolTable& tools, const PresetTable& presets,
                  std::function<std::shared_ptr<const Mesh>()> received_mesh, const tf2_ros::Buffer* tf = nullptr);

 private:
  void on_goal(const PlanJobGoalConstPtr& goal);

  std::string frame_id_;
  JobGoalContext context_;
  SetupFramePublisher setup_frames_;
  ::ros::Publisher job_markers_, stock_markers_;
  actionlib::SimpleActionServer<PlanJobAction> server_;
};

}  // namespace rosmill::edge
