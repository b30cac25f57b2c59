// toolpath_planner: plans 3-axis toolpaths with rosmill::plan(request) from the mesh (`mesh` topic, from
// stl_loader) or from a scan (`cloud_topic` PointCloud2, brought into the workpiece frame with tf2, waiting at most
// tf_timeout for the transform, then prepared by the same input step as `rosmill plan`: parameters orient, origin,
// voxel, outliers, holes, named after its options; origin defaults to keep, the frame tf gave). Strategies, presets
// and templates by name (`presets`: the preset table, default presets.yaml next to the tool table). Publishes the job
// latched on `toolpath` (msg::ToolpathJob) and its view on `toolpath_markers`;
// replans on the `plan` service and the `plan_toolpath` action (several items, per-item results, progress
// feedback, cancel) for another setup, strategy or tool. An input it rejects (no points, no transform, a broken
// mesh) is logged, reported on /diagnostics, and its reason is what a later plan request for that source is
// answered with. A toolpath for a setup other than +Z is stamped with the setup's frame, published on tf.
// Planning on input is cancelled by a newer input and by shutdown; it and the plan service stop after
// `service_time_limit` seconds (the plan_toolpath action has no limit: it reports progress and can be cancelled).
#include <actionlib/server/simple_action_server.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <shape_msgs/Mesh.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>

#include "rosmill/Plan.h"
#include "rosmill/PlanToolpathAction.h"
#include "rosmill/cloud/cloud_input.hpp"
#include "rosmill/error.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/finish_goal.hpp"
#include "rosmill/ros/input_diagnostics.hpp"
#include "rosmill/ros/input_slot.hpp"
#include "rosmill/ros/markers.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/plan_goal.hpp"
#include "rosmill/ros/setup_frames.hpp"
#include "rosmill/ros/transform_wait.hpp"

namespace rosmill::edge {
namespace {

// A Plan request and a PlanToolpath item have the same fields.
template <typename Msg>
msg::PlanItem item_of(const Msg& m) {
  msg::PlanItem item;
  item.setup = m.setup;
  item.direction = m.direction;
  item.strategy = m.strategy;
  item.tool_id = m.tool_id;
  item.source = m.source;
  item.parameters = m.parameters;
  return item;
}

struct PlanOutcome {
  Job job;
  SetupFrame setup;
  msg::ToolpathJob job_msg;
  msg::PlanStatistics statistics;
};

class ToolpathPlanner {
 public:
  ToolpathPlanner(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh)
      : frame_id_(string_param(pnh, "frame_id", "workpiece")),
        strategy_(string_param(pnh, "strategy", "raster")),
        cloud_strategy_(string_param(pnh, "cloud_strategy", "cloud-rough")),
        setup_(string_param(pnh, "setup", "+Z")),
        tool_id_(int_param(pnh, "tool_id", 2, 1, 9999)),
        tools_(tool_table_param(pnh, "tool_table")),
        defaults_(plan_defaults_param(pnh)),
        presets_(presets_param(pnh)),
        cloud_input_(cloud_input_param(pnh)),
        option_prefix_(pnh.resolveName("") + "/"),
        tf_timeout_(double_param(pnh, "tf_timeout", 1.0, 0.0, 30.0)),
        rapid_feed_(double_param(pnh, "rapid_feed", 5000.0, 1.0, 1e6)),
        time_limit_(double_param(pnh, "service_time_limit", 30.0, 0.001, 86400.0)),
        plan_on_input_(bool_param(pnh, "plan_on_input", true)),
        tf_listener_(tf_buffer_),
        diagnostics_(nh),
        action_(nh, "plan_toolpath", [this](const PlanToolpathGoalConstPtr& goal) { on_goal(goal); }, false) {
    tools_.get(tool_id_);  // the default tool must exist
    named_setup(setup_, "parameter " + pnh.resolveName("setup"));
    require_strategy(strategy_, "parameter " + pnh.resolveName("strategy"));
    require_strategy(cloud_strategy_, "parameter " + pnh.resolveName("cloud_strategy"));
    job_pub_ = nh.advertise<msg::ToolpathJob>("toolpath", 1, true);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("toolpath_markers", 1, true);
    mesh_sub_ = nh.subscribe("mesh", 1, &ToolpathPlanner::on_mesh, this);
    cloud_sub_ = nh.subscribe(string_param(pnh, "cloud_topic", "cloud"), 1, &ToolpathPlanner::on_cloud, this);
    plan_srv_ = nh.advertiseService("plan", &ToolpathPlanner::on_plan, this);
    action_.start();
  }

 private:
  void require_strategy(const std::string& name, const std::string& where) const {
    check_plan_name(name, &presets_, where);
  }

  void on_mesh(const shape_msgs::Mesh::ConstPtr& msg) {
    try {
      auto mesh = std::make_shared<const Mesh>(from_mesh_msg(*msg, "mesh"));
      if (mesh->faces.empty()) throw Error("mesh", "has no triangles");
      mesh_.accept(mesh);
      accepted("mesh", std::to_string(mesh->faces.size()) + " triangles");
    } catch (const std::exception& e) {
      mesh_.reject(e.what());
      rejected("mesh", e.what());
    }
  }

  void on_cloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
    try {
      const std::string where = "cloud in frame '" + msg->header.frame_id + "'";
      const PointCloud raw = from_cloud_msg(*msg, to_workpiece(msg->header), where);
      if (raw.points.empty()) throw Error(where, "has no finite points");
      CloudPrepReport report;
      auto cloud =
          std::make_shared<const PointCloud>(prepare_input_cloud(raw.points, cloud_input_, option_prefix_, &report));
      ROS_DEBUG("toolpath_planner: cloud prepared:\n%s", format_prep_report(report).c_str());
      cloud_.accept(cloud);
      accepted("cloud", std::to_string(cloud->points.size()) + " points in " + frame_id_);
    } catch (const std::exception& e) {
      cloud_.reject(e.what());
      rejected("cloud", e.what());
    }
  }

  // A new input (accepted or not) supersedes the plan of the one before, which stops at its next progress check.
  void accepted(const char* source, const std::string& summary) {
    const uint64_t generation = ++inputs_;
    {
      std::lock_guard<std::mutex> lock(latest_mutex_);
      latest_ = source;
    }
    ROS_INFO("toolpath_planner: %s of %s", source, summary.c_str());
    diagnostics_.accepted(source, summary);
    if (plan_on_input_) plan_and_publish(source, generation);
  }

  void rejected(const char* source, const std::string& why) {
    ++inputs_;
    ROS_ERROR("toolpath_planner: %s", why.c_str());
    diagnostics_.rejected(source, why);
  }

  // The cloud frame -> workpiece frame transform, waiting at most tf_timeout for it.
  Eigen::Isometry3d to_workpiece(const std_msgs::Header& header) {
    if (header.frame_id.empty() || header.frame_id == frame_id_) return Eigen::Isometry3d::Identity();
    return wait_for_transform(tf_buffer_, frame_id_, header.frame_id, header.stamp, tf_timeout_,
                              "cloud in frame '" + header.frame_id + "'");
  }

  // Plans one item (throws Error with the reason); `progress` may cancel.
  PlanOutcome plan_item(const msg::PlanItem& item, const PlanProgress& progress) {
    std::shared_ptr<const Mesh> mesh;
    std::shared_ptr<const PointCloud> cloud;
    std::string source = item.source;
    if (source.empty()) {
      std::lock_guard<std::mutex> lock(latest_mutex_);
      source = latest_;
    }
    if (source.empty()) throw Error("plan", "no input yet: publish a mesh or a cloud first");
    if (source == "mesh")
      mesh = mesh_.require();
    else if (source == "cloud")
      cloud = cloud_.require();
    else
      throw Error("source", "must be \"mesh\", \"cloud\" or empty, got \"" + source + "\"");
    PlanOutcome out;
    out.setup = resolve_setup(item.setup, from_direction_msg(item.direction));
    const std::string strategy = !item.strategy.empty() ? item.strategy : (mesh ? strategy_ : cloud_strategy_);
    const core::Tool& tool = tools_.get(item.tool_id == 0 ? tool_id_ : item.tool_id);
    PlanningRequest request;
    request.strategy = strategy;
    request.params = from_plan_parameters(item.parameters, tool, defaults_);
    request.progress = progress;
    request.presets = &presets_;
    // A template runs its presets' own tools (one per stage).
    if (presets_.find_template(strategy)) request.params.tool = core::Tool{};

    const ::ros::WallTime t0 = ::ros::WallTime::now();
    PlanInput& input = request.input;
    input.setup = out.setup;  // plan() turns the part for the setup
    input.mesh = mesh.get();
    input.cloud = cloud.get();
    if (cloud) input.holes = cloud_hole_policy(cloud_input_, option_prefix_);
    out.job = plan(request);
    // The toolpath is in the setup's frame; the markers are drawn back in the workpiece frame.
    std_msgs::Header header;
    header.frame_id = setup_frames_.publish(frame_id_, out.setup);
    header.stamp = ::ros::Time::now();
    out.job_msg = to_job_msg(out.job, out.setup, header);
    out.statistics = to_statistics_msg(out.job, (::ros::WallTime::now() - t0).toSec(), rapid_feed_);
    return out;
  }

  void publish(const PlanOutcome& out) {
    job_pub_.publish(out.job_msg);
    std_msgs::Header header = out.job_msg.header;
    header.frame_id = frame_id_;
    marker_pub_.publish(toolpath_markers(out.job, out.setup, header));
    ROS_INFO("toolpath_planner: %u toolpaths, %u moves for setup %s in %.3f s", out.statistics.toolpaths,
             out.statistics.moves, out.setup.name.c_str(), out.statistics.planning_time);
  }

  // Progress for the plans outside the action: stops at shutdown, at the time limit, and (for a plan on input)
  // when a newer input arrives. `timed_out` tells the caller which of them it was.
  PlanProgress limited(std::shared_ptr<std::atomic<bool>> timed_out, uint64_t generation = 0) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(time_limit_);
    return [this, timed_out, generation, deadline](double) {
      if (generation != 0 && inputs_.load() != generation) return false;
      if (std::chrono::steady_clock::now() > deadline) {
        *timed_out = true;
        return false;
      }
      return ::ros::ok();
    };
  }

  std::string over_time_limit() const {
    return "stopped after the time limit of " + std::to_string(time_limit_) +
           " s for plans outside the action (parameter service_time_limit): plan it with the plan_toolpath "
           "action, which reports progress and can be cancelled";
  }

  void plan_and_publish(const std::string& source, uint64_t generation) {
    msg::PlanItem item;
    item.setup = setup_;
    item.source = source;
    auto timed_out = std::make_shared<std::atomic<bool>>(false);
    try {
      publish(plan_item(item, limited(timed_out, generation)));
    } catch (const std::exception& e) {
      if (inputs_.load() != generation)
        ROS_INFO("toolpath_planner: the plan of the %s before was superseded by a newer input", source.c_str());
      else
        ROS_ERROR("toolpath_planner: %s", *timed_out ? ("plan: " + over_time_limit()).c_str() : e.what());
    }
  }

  bool on_plan(Plan::Request& req, Plan::Response& res) {
    try {
      auto timed_out = std::make_shared<std::atomic<bool>>(false);
      PlanOutcome out;
      try {
        out = plan_item(item_of(req), limited(timed_out));
      } catch (const Error&) {
        if (*timed_out) throw Error("plan", over_time_limit());
        throw;
      }
      if (!req.preview) publish(out);
      res.job = std::move(out.job_msg);
      res.statistics = out.statistics;
      res.success = true;
      res.message = plan_summary(res.statistics);
    } catch (const std::exception& e) {
      res.success = false;
      res.message = e.what();
      ROS_WARN("toolpath_planner: plan: %s", e.what());
    }
    return true;
  }

  void on_goal(const PlanToolpathGoalConstPtr& goal) {
    PlanGoalHooks hooks;
    hooks.cancel_requested = [this] { return action_.isPreemptRequested(); };
    hooks.feedback = [this](const PlanToolpathFeedback& fb) { action_.publishFeedback(fb); };
    hooks.plan_item = [&](size_t i, const PlanProgress& progress) {
      PlanOutcome out = plan_item(goal->items[i], progress);
      if (action_.isPreemptRequested()) throw Error("plan", "cancelled");
      if (!goal->preview) publish(out);
      msg::PlanItemResult r;
      r.job = std::move(out.job_msg);
      r.statistics = out.statistics;
      return r;
    };
    bool cancelled = false;
    const PlanToolpathResult result = run_plan_goal(*goal, hooks, cancelled);
    finish_goal(action_, result, cancelled, result.success);
  }

  std::string frame_id_, strategy_, cloud_strategy_, setup_;
  int tool_id_;
  ToolTable tools_;
  PlanParams defaults_;
  PresetTable presets_;
  CloudInputOptions cloud_input_;
  std::string option_prefix_;
  double tf_timeout_, rapid_feed_, time_limit_;
  bool plan_on_input_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  InputDiagnostics diagnostics_;
  SetupFramePublisher setup_frames_;
  actionlib::SimpleActionServer<PlanToolpathAction> action_;
  InputSlot<Mesh> mesh_{"mesh"};
  InputSlot<PointCloud> cloud_{"cloud"};
  std::atomic<uint64_t> inputs_{0};  // inputs received (accepted or not)
  std::mutex latest_mutex_;
  std::string latest_;               // the source last accepted: what a plan without `source` plans
  ::ros::Publisher job_pub_, marker_pub_;
  ::ros::Subscriber mesh_sub_, cloud_sub_;
  ::ros::ServiceServer plan_srv_;
};

}  // namespace
}  // namespace rosmill::edge

int main(int argc, char** argv) {
  // Two threads: a cloud waiting for its transform must not block the services.
  return rosmill::edge::run_node<rosmill::edge::ToolpathPlanner>(argc, argv, "toolpath_planner", 2);
}
