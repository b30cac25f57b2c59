// toolpath_planner: plans 3-axis toolpaths with rosmill::plan() from the mesh (`mesh` topic, from stl_loader) or
// from a scan (`cloud` PointCloud2, brought into the workpiece frame with tf2). Publishes the job latched on
// `toolpath` (ToolpathJobMsg) and its view on `toolpath_markers`; replans on the `plan` service and the
// `plan_toolpath` action (progress feedback, cancel) for another setup, strategy or tool.
#include <actionlib/server/simple_action_server.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <shape_msgs/Mesh.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <memory>
#include <mutex>

#include "rosmill/Plan.h"
#include "rosmill/PlanToolpathAction.h"
#include "rosmill/error.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/markers.hpp"
#include "rosmill/ros/params.hpp"

namespace rosmill::edge {
namespace {

// What a Plan request, a PlanToolpath goal and an automatic replan have in common.
struct PlanRequest {
  std::string setup;
  Vec3 direction = Vec3::Zero();
  std::string strategy;
  int tool_id = 0;
  std::string source;
  PlanParametersMsg parameters;
};

template <typename Msg>
PlanRequest request_of(const Msg& m) {
  return {m.setup, from_direction_msg(m.direction), m.strategy, m.tool_id, m.source, m.parameters};
}

struct PlanOutcome {
  Job job;
  SetupFrame setup;
  ToolpathJobMsg job_msg;
  PlanStatisticsMsg statistics;
};

class ToolpathPlanner {
 public:
  ToolpathPlanner(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh)
      : nh_(nh),
        frame_id_(string_param(pnh, "frame_id", "workpiece")),
        strategy_(string_param(pnh, "strategy", "raster")),
        cloud_strategy_(string_param(pnh, "cloud_strategy", "cloud-rough")),
        setup_(string_param(pnh, "setup", "+Z")),
        tool_id_(int_param(pnh, "tool_id", 1, 1, 9999)),
        tools_(tool_table_param(pnh, "tools")),
        defaults_(plan_defaults_param(pnh)),
        tf_timeout_(double_param(pnh, "tf_timeout", 1.0, 0.0, 30.0)),
        rapid_feed_(double_param(pnh, "rapid_feed", 5000.0, 1.0, 1e6)),
        plan_on_input_(bool_param(pnh, "plan_on_input", true)),
        tf_listener_(tf_buffer_),
        action_(nh, "plan_toolpath", [this](const PlanToolpathGoalConstPtr& goal) { on_goal(goal); }, false) {
    if (tools_.empty()) throw Error("parameter " + pnh.resolveName("tools"), "the tool table is empty");
    find_tool(tools_, tool_id_);   // the default tool must exist
    named_setup(setup_, "parameter " + pnh.resolveName("setup"));
    job_pub_ = nh.advertise<ToolpathJobMsg>("toolpath", 1, true);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("toolpath_markers", 1, true);
    mesh_sub_ = nh.subscribe("mesh", 1, &ToolpathPlanner::on_mesh, this);
    cloud_sub_ = nh.subscribe(string_param(pnh, "cloud_topic", "cloud"), 1, &ToolpathPlanner::on_cloud, this);
    plan_srv_ = nh.advertiseService("plan", &ToolpathPlanner::on_plan, this);
    action_.start();
  }

 private:
  void on_mesh(const shape_msgs::Mesh::ConstPtr& msg) {
    try {
      auto mesh = std::make_shared<const Mesh>(from_mesh_msg(*msg));
      {
        std::lock_guard<std::mutex> lock(input_mutex_);
        mesh_ = mesh;
        latest_ = "mesh";
      }
      ROS_INFO("toolpath_planner: mesh of %zu triangles", mesh->faces.size());
      if (plan_on_input_) plan_and_publish(default_request("mesh"));
    } catch (const std::exception& e) {
      ROS_ERROR("toolpath_planner: mesh: %s", e.what());
    }
  }

  void on_cloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
    try {
      auto cloud = std::make_shared<const PointCloud>(from_cloud_msg(*msg, to_workpiece(msg->header), "cloud"));
      if (cloud->points.empty()) throw Error("cloud", "has no finite points");
      {
        std::lock_guard<std::mutex> lock(input_mutex_);
        cloud_ = cloud;
        latest_ = "cloud";
      }
      ROS_INFO("toolpath_planner: cloud of %zu points in %s", cloud->points.size(), frame_id_.c_str());
      if (plan_on_input_) plan_and_publish(default_request("cloud"));
    } catch (const std::exception& e) {
      ROS_ERROR("toolpath_planner: %s", e.what());
    }
  }

  // The cloud frame -> workpiece frame transform, waiting at most tf_timeout for it.
  Eigen::Isometry3d to_workpiece(const std_msgs::Header& header) {
    if (header.frame_id.empty() || header.frame_id == frame_id_) return Eigen::Isometry3d::Identity();
    std::string why;
    if (!tf_buffer_.canTransform(frame_id_, header.frame_id, header.stamp, ::ros::Duration(tf_timeout_), &why)) {
      // A cloud stamped a little after the latest transform is still usable with the latest one.
      if (!tf_buffer_.canTransform(frame_id_, header.frame_id, ::ros::Time(0), &why))
        throw Error("cloud in frame '" + header.frame_id + "'",
                    "no transform to '" + frame_id_ + "' within " + std::to_string(tf_timeout_) + " s (" + why + ")");
      return tf2::transformToEigen(tf_buffer_.lookupTransform(frame_id_, header.frame_id, ::ros::Time(0)));
    }
    return tf2::transformToEigen(tf_buffer_.lookupTransform(frame_id_, header.frame_id, header.stamp));
  }

  PlanRequest default_request(const std::string& source) const {
    PlanRequest r;
    r.setup = setup_;
    r.source = source;
    return r;
  }

  // Plans a request (throws Error with the reason); `progress` may cancel.
  PlanOutcome plan_request(const PlanRequest& req, const PlanProgress& progress) {
    std::shared_ptr<const Mesh> mesh;
    std::shared_ptr<const PointCloud> cloud;
    std::string source = req.source;
    {
      std::lock_guard<std::mutex> lock(input_mutex_);
      if (source.empty()) source = latest_;
      mesh = mesh_;
      cloud = cloud_;
    }
    if (source.empty()) throw Error("plan", "no input yet: publish a mesh or a cloud first");
    if (source != "mesh" && source != "cloud")
      throw Error("source", "must be \"mesh\", \"cloud\" or empty, got \"" + source + "\"");
    if (source == "mesh" && !mesh) throw Error("source", "no mesh has been received");
    if (source == "cloud" && !cloud) throw Error("source", "no cloud has been received");

    PlanOutcome out;
    out.setup = resolve_setup(req.setup, req.direction);
    const std::string strategy =
        !req.strategy.empty() ? req.strategy : (source == "mesh" ? strategy_ : cloud_strategy_);
    const Tool& tool = find_tool(tools_, req.tool_id == 0 ? tool_id_ : req.tool_id);
    const PlanParams params = from_plan_parameters(req.parameters, tool, defaults_);

    const ::ros::WallTime t0 = ::ros::WallTime::now();
    PlanInput input;
    Mesh mesh_in_frame;
    PointCloud cloud_in_frame;
    if (source == "mesh") {
      mesh_in_frame = mesh_in_setup(*mesh, out.setup);
      input.mesh = &mesh_in_frame;
    } else {
      cloud_in_frame = cloud_in_setup(*cloud, out.setup);
      input.cloud = &cloud_in_frame;
    }
    out.job = plan(strategy, input, params, progress);
    std_msgs::Header header;
    header.frame_id = frame_id_;
    header.stamp = ::ros::Time::now();
    out.job_msg = to_job_msg(out.job, out.setup, header);
    out.statistics = to_statistics_msg(out.job, (::ros::WallTime::now() - t0).toSec(), rapid_feed_);
    return out;
  }

  void publish(const PlanOutcome& out) {
    job_pub_.publish(out.job_msg);
    marker_pub_.publish(toolpath_markers(out.job, out.setup, out.job_msg.header));
    ROS_INFO("toolpath_planner: %u toolpaths, %u moves for setup %s in %.3f s", out.statistics.toolpaths,
             out.statistics.moves, out.setup.name.c_str(), out.statistics.planning_time);
  }

  void plan_and_publish(const PlanRequest& req) {
    try {
      publish(plan_request(req, {}));
    } catch (const std::exception& e) {
      ROS_ERROR("toolpath_planner: %s", e.what());
    }
  }

  bool on_plan(Plan::Request& req, Plan::Response& res) {
    try {
      PlanOutcome out = plan_request(request_of(req), {});
      publish(out);
      res.job = std::move(out.job_msg);
      res.statistics = out.statistics;
      res.success = true;
      res.message = "planned " + std::to_string(res.statistics.moves) + " moves";
    } catch (const std::exception& e) {
      res.success = false;
      res.message = e.what();
      ROS_WARN("toolpath_planner: plan: %s", e.what());
    }
    return true;
  }

  void on_goal(const PlanToolpathGoalConstPtr& goal) {
    PlanToolpathResult result;
    ::ros::WallTime last_feedback;
    const PlanProgress progress = [&](double fraction) {
      // Feedback at most every 0.1 s: a strategy may report progress per raster line.
      if ((::ros::WallTime::now() - last_feedback).toSec() > 0.1) {
        PlanToolpathFeedback fb;
        fb.progress = float(fraction);
        fb.stage = "planning";
        action_.publishFeedback(fb);
        last_feedback = ::ros::WallTime::now();
      }
      return !action_.isPreemptRequested() && ::ros::ok();
    };
    try {
      PlanOutcome out = plan_request(request_of(*goal), progress);
      if (action_.isPreemptRequested()) throw Error("plan", "cancelled");
      PlanToolpathFeedback fb;
      fb.progress = 1.0f;
      fb.stage = "publishing";
      action_.publishFeedback(fb);
      publish(out);
      result.job = std::move(out.job_msg);
      result.statistics = out.statistics;
      result.success = true;
      result.message = "planned " + std::to_string(result.statistics.moves) + " moves";
      action_.setSucceeded(result);
    } catch (const std::exception& e) {
      result.success = false;
      result.message = e.what();
      if (action_.isPreemptRequested())
        action_.setPreempted(result, result.message);
      else
        action_.setAborted(result, result.message);
    }
  }

  ::ros::NodeHandle nh_;
  std::string frame_id_, strategy_, cloud_strategy_, setup_;
  int tool_id_;
  std::vector<Tool> tools_;
  PlanParams defaults_;
  double tf_timeout_, rapid_feed_;
  bool plan_on_input_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  actionlib::SimpleActionServer<PlanToolpathAction> action_;
  std::mutex input_mutex_;
  std::shared_ptr<const Mesh> mesh_;
  std::shared_ptr<const PointCloud> cloud_;
  std::string latest_;
  ::ros::Publisher job_pub_, marker_pub_;
  ::ros::Subscriber mesh_sub_, cloud_sub_;
  ::ros::ServiceServer plan_srv_;
};

}  // namespace
}  // namespace rosmill::edge

int main(int argc, char** argv) {
  ros::init(argc, argv, "toolpath_planner");
  ros::NodeHandle nh, pnh("~");
  try {
    rosmill::edge::ToolpathPlanner node(nh, pnh);
    // Two threads: a cloud waiting for its transform must not block the services.
    ros::AsyncSpinner spinner(2);
    spinner.start();
    ros::waitForShutdown();
  } catch (const std::exception& e) {
    ROS_FATAL("toolpath_planner: %s", e.what());
    return 1;
  }
  return 0;
}
