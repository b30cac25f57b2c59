#include "rosmill/ros/item_planner.hpp"

#include <ros/ros.h>

#include "rosmill/cloud/cloud_prep.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/params.hpp"

namespace rosmill::edge {

PlannerSettings planner_settings(const ::ros::NodeHandle& pnh) {
  PlannerSettings s;
  s.frame_id = string_param(pnh, "frame_id", "workpiece");
  s.strategy = string_param(pnh, "strategy", "raster");
  s.cloud_strategy = string_param(pnh, "cloud_strategy", "cloud-rough");
  s.setup = string_param(pnh, "setup", "+Z");
  s.tool_id = int_param(pnh, "tool_id", 2, 1, 9999);
  s.tools = tool_table_param(pnh, "tool_table");
  s.defaults = plan_defaults_param(pnh);
  s.presets = presets_param(pnh);
  s.cloud_input = cloud_input_param(pnh);
  s.option_prefix = pnh.resolveName("") + "/";
  const std::string machine = string_param(pnh, "machine", "");
  if (!machine.empty()) {
    s.machine = gcode::load_machine_limits(machine);
    s.trajectory = s.machine->trajectory;
  }
  s.tools.get(s.tool_id);  // the default tool must exist
  named_setup(s.setup, "parameter " + pnh.resolveName("setup"));
  check_plan_name(s.strategy, &s.presets, "parameter " + pnh.resolveName("strategy"));
  check_plan_name(s.cloud_strategy, &s.presets, "parameter " + pnh.resolveName("cloud_strategy"));
  return s;
}

PointCloud prepared_cloud(const sensor_msgs::PointCloud2& msg, const Eigen::Isometry3d& to_workpiece,
                          const PlannerSettings& settings) {
  const std::string where = "cloud in frame '" + msg.header.frame_id + "'";
  const PointCloud raw = from_cloud_msg(msg, to_workpiece, where);
  if (raw.points.empty()) throw Error(where, "has no finite points");
  CloudPrepReport report;
  PointCloud cloud = prepare_input_cloud(raw.points, settings.cloud_input, settings.option_prefix, &report);
  ROS_DEBUG("cloud prepared:\n%s", format_prep_report(report).c_str());
  return cloud;
}

PlanDeadline::PlanDeadline(double seconds, std::function<bool()> wanted)
    : seconds_(seconds),
      deadline_(std::chrono::steady_clock::now() +
                std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds))),
      wanted_(std::move(wanted)) {}

PlanProgress PlanDeadline::progress() const {
  return [deadline = deadline_, wanted = wanted_, timed_out = timed_out_](double) {
    if (wanted && !wanted()) return false;
    if (std::chrono::steady_clock::now() > deadline) {
      *timed_out = true;
      return false;
    }
    return ::ros::ok();
  };
}

std::string PlanDeadline::over_limit() const {
  return "stopped after the time limit of " + std::to_string(seconds_) +
         " s for plans outside the action (parameter service_time_limit): plan it with the plan_toolpath "
         "action, which reports progress and can be cancelled";
}

PlanOutcome ItemPlanner::plan(const msg::PlanItem& item, const PlanInputs& inputs, const PlanProgress& progress) {
  const PlanSource source = inputs.select(item.source);
  PlanOutcome out;
  out.setup = resolve_setup(item.setup, from_direction_msg(item.direction));
  const std::string strategy =
      !item.strategy.empty() ? item.strategy : (source.mesh ? settings_.strategy : settings_.cloud_strategy);
  const core::Tool& tool = settings_.tools.get(item.tool_id == 0 ? settings_.tool_id : item.tool_id);
  PlanningRequest request;
  request.strategy = strategy;
  request.params = from_plan_parameters(item.parameters, tool, settings_.defaults);
  request.progress = progress;
  request.presets = &settings_.presets;
  // A template runs its presets' own tools (one per stage).
  if (settings_.presets.find_template(strategy)) request.params.tool = core::Tool{};

  const ::ros::WallTime t0 = ::ros::WallTime::now();
  PlanInput& input = request.input;
  input.setup = out.setup;  // plan() turns the part for the setup
  input.mesh = source.mesh.get();
  input.cloud = source.cloud.get();
  if (source.cloud) input.holes = cloud_hole_policy(settings_.cloud_input, settings_.option_prefix);
  out.job = rosmill::core::plan(request);
  // The toolpath is in the setup's frame, published on tf.
  std_msgs::Header header;
  header.frame_id = setup_frames_.publish(settings_.frame_id, out.setup);
  header.stamp = ::ros::Time::now();
  out.job_msg = to_job_msg(out.job, out.setup, header);
  out.statistics = to_statistics_msg(out.job, (::ros::WallTime::now() - t0).toSec(), settings_.trajectory,
                                     settings_.machine ? &*settings_.machine : nullptr);
  return out;
}

}  // namespace rosmill::edge
