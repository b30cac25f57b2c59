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
// The `plan_job` action runs a job (rosmill job's YAML) on the in-process stock, publishing the toolpaths of each
// operation on `job_markers` and the stock it left on `stock_markers`.
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <shape_msgs/Mesh.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <memory>

#include "rosmill/Plan.h"
#include "rosmill/error.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/input_diagnostics.hpp"
#include "rosmill/ros/item_planner.hpp"
#include "rosmill/ros/job_goal.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/plan_action.hpp"
#include "rosmill/ros/plan_goal.hpp"
#include "rosmill/ros/transform_wait.hpp"

namespace rosmill::edge {
namespace {

class ToolpathPlanner {
 public:
  ToolpathPlanner(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh)
      : planner_(planner_settings(pnh)),
        tf_timeout_(double_param(pnh, "tf_timeout", 1.0, 0.0, 30.0)),
        time_limit_(double_param(pnh, "service_time_limit", 30.0, 0.001, 86400.0)),
        plan_on_input_(bool_param(pnh, "plan_on_input", true)),
        tf_listener_(tf_buffer_),
        diagnostics_(nh),
        out_(nh, frame_id()),
        plans_(nh, planner_, inputs_, out_),
        jobs_(nh, pnh, frame_id(), planner_.settings().tools, planner_.settings().presets,
              [this] { return inputs_.select("mesh").mesh; }, &tf_buffer_) {
    mesh_sub_ = nh.subscribe("mesh", 1, &ToolpathPlanner::on_mesh, this);
    cloud_sub_ = nh.subscribe(string_param(pnh, "cloud_topic", "cloud"), 1, &ToolpathPlanner::on_cloud, this);
    plan_srv_ = nh.advertiseService("plan", &ToolpathPlanner::on_plan, this);
  }

 private:
  const std::string& frame_id() const { return planner_.settings().frame_id; }

  void on_mesh(const shape_msgs::Mesh::ConstPtr& msg) {
    try {
      auto mesh = std::make_shared<const Mesh>(from_mesh_msg(*msg, "mesh"));
      if (mesh->faces.empty()) throw Error("mesh", "has no triangles");
      const size_t triangles = mesh->faces.size();
      accepted("mesh", inputs_.accept_mesh(std::move(mesh)), std::to_string(triangles) + " triangles");
    } catch (const std::exception& e) {
      rejected("mesh", e.what());
    }
  }

  void on_cloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
    try {
      auto cloud = std::make_shared<const PointCloud>(prepared_cloud(*msg, to_workpiece(msg->header), planner_.settings()));
      const size_t points = cloud->points.size();
      accepted("cloud", inputs_.accept_cloud(std::move(cloud)), std::to_string(points) + " points in " + frame_id());
    } catch (const std::exception& e) {
      rejected("cloud", e.what());
    }
  }

  void accepted(const char* source, uint64_t generation, const std::string& summary) {
    ROS_INFO("toolpath_planner: %s of %s", source, summary.c_str());
    diagnostics_.accepted(source, summary);
    if (plan_on_input_) plan_on_input(source, generation);
  }

  void rejected(const char* source, const std::string& why) {
    inputs_.reject(source, why);
    ROS_ERROR("toolpath_planner: %s", why.c_str());
    diagnostics_.rejected(source, why);
  }

  // The cloud frame -> workpiece frame transform, waiting at most tf_timeout for it.
  Eigen::Isometry3d to_workpiece(const std_msgs::Header& header) {
    if (header.frame_id.empty() || header.frame_id == frame_id()) return Eigen::Isometry3d::Identity();
    return wait_for_transform(tf_buffer_, frame_id(), header.frame_id, header.stamp, tf_timeout_,
                              "cloud in frame '" + header.frame_id + "'");
  }

  // A newer input supersedes this plan, which stops at its next progress check.
  void plan_on_input(const std::string& source, uint64_t generation) {
    msg::PlanItem item;
    item.setup = planner_.settings().setup;
    item.source = source;
    const PlanDeadline deadline(time_limit_, [this, generation] { return inputs_.current(generation); });
    try {
      out_.publish(planner_.plan(item, inputs_, deadline.progress()));
    } catch (const std::exception& e) {
      if (!inputs_.current(generation))
        ROS_INFO("toolpath_planner: the plan of the %s before was superseded by a newer input", source.c_str());
      else
        ROS_ERROR("toolpath_planner: %s", deadline.timed_out() ? ("plan: " + deadline.over_limit()).c_str() : e.what());
    }
  }

  bool on_plan(Plan::Request& req, Plan::Response& res) {
    const PlanDeadline deadline(time_limit_);
    try {
      PlanOutcome out = planner_.plan(plan_item_of(req), inputs_, deadline.progress());
      if (!req.preview) out_.publish(out);
      res.job = std::move(out.job_msg);
      res.statistics = out.statistics;
      res.success = true;
      res.message = plan_summary(res.statistics);
    } catch (const std::exception& e) {
      res.success = false;
      res.message = deadline.timed_out() ? "plan: " + deadline.over_limit() : e.what();
      ROS_WARN("toolpath_planner: plan: %s", res.message.c_str());
    }
    return true;
  }

  ItemPlanner planner_;
  double tf_timeout_, time_limit_;
  bool plan_on_input_;
  PlanInputs inputs_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  InputDiagnostics diagnostics_;
  ToolpathPublisher out_;
  PlanActionServer plans_;  // the plan_toolpath action
  JobActionServer jobs_;    // the plan_job action
  ::ros::Subscriber mesh_sub_, cloud_sub_;
  ::ros::ServiceServer plan_srv_;
};

}  // namespace
}  // namespace rosmill::edge

int main(int argc, char** argv) {
  // Two threads: a cloud waiting for its transform must not block the services.
  return rosmill::edge::run_node<rosmill::edge::ToolpathPlanner>(argc, argv, "toolpath_planner", 2);
}
