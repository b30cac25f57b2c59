// scan_registrar: from the scanner to the workpiece frame. Views arriving on `scan_views` (PointCloud2) are
// collected on request, each through the sensor's pose from tf at its stamp, and fused (~start, ~add_view,
// ~finish, ~reset: std_srvs/Trigger; the fused cloud latched on `fused_cloud` in ~fixed_frame). `~register`
// (rosmill/RegisterScan) finds the design (~design, an STL; else the latest `mesh`) in a scan with no initial guess
// and publishes the pose as the static transform ~fixed_frame -> ~workpiece_frame (REP 105: `table` ->
// `workpiece`), which every plan, marker and program of the mesh pipeline is in, and the gcode_bridge turns into
// the program's work offset. `~inspect` (rosmill/InspectScan) compares a scan of the machined part with the
// design. Both publish the scan coloured by its distance to the design on `scan_deviation_markers`. `~save`
// (rosmill/SaveScan) writes a scan in a frame, e.g. the raw stock's in the workpiece frame for a job's stock.
// With ~every_cloud_a_view each cloud that comes is the session's next view (up to ~max_views) without add_view:
// a scanner that publishes one cloud a capture, or a recording replayed (launch/replay.launch). ~sensor_frame, when
// set, is the frame of every cloud whatever its header says.
#include <ros/ros.h>
#include <shape_msgs/Mesh.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <memory>
#include <mutex>

#include "rosmill/SaveScan.h"
#include "rosmill/error.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/input_diagnostics.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/scan_params.hpp"
#include "rosmill/ros/scan_report_msg.hpp"
#include "rosmill/ros/scan_session.hpp"
#include "rosmill/ros/transform_wait.hpp"

namespace rosmill::edge {
namespace {

class ScanRegistrar {
 public:
  ScanRegistrar(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh)
      : workpiece_frame_(string_param(pnh, "workpiece_frame", "workpiece")),
        view_timeout_(double_param(pnh, "view_timeout", 5.0, 0.1, 600.0)),
        tolerance_(double_param(pnh, "tolerance", 0.05, 0.0, 100.0)),
        tf_listener_(tf_),
        session_(tf_, string_param(pnh, "fixed_frame", "table"), double_param(pnh, "transform_timeout", 0.5, 0, 30)),
        diagnostics_(nh, "scan") {
    read_scan_options(pnh, fusion_, registration_);
    const bool every_cloud = bool_param(pnh, "every_cloud_a_view", false);
    if (every_cloud) session_.take_every_cloud(static_cast<size_t>(int_param(pnh, "max_views", 0, 0, 10000)));
    session_.take_clouds_in(string_param(pnh, "sensor_frame", ""));
    const std::string design = string_param(pnh, "design", "");
    if (!design.empty()) {
      StlReadOptions o;
      o.units = parse_units(string_param(pnh, "design_units", "mm"), "parameter design_units");
      design_ = std::make_shared<const Mesh>(read_stl(design, o));
    }
    fused_pub_ = nh.advertise<sensor_msgs::PointCloud2>("fused_cloud", 1, true);
    markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("scan_deviation_markers", 1, true);
    // Every cloud a view: the queue holds the clouds that come while one waits for its pose (a bag played fast).
    cloud_sub_ = nh.subscribe("scan_views", every_cloud ? 16 : 2, &ScanSession::on_cloud, &session_);
    if (!design_) mesh_sub_ = nh.subscribe("mesh", 1, &ScanRegistrar::on_mesh, this);
    services_ = {pnh.advertiseService("start", &ScanRegistrar::on_start, this),
                 pnh.advertiseService("add_view", &ScanRegistrar::on_add_view, this),
                 pnh.advertiseService("finish", &ScanRegistrar::on_finish, this),
                 pnh.advertiseService("reset", &ScanRegistrar::on_reset, this),
                 pnh.advertiseService("register", &ScanRegistrar::on_register, this),
                 pnh.advertiseService("inspect", &ScanRegistrar::on_inspect, this),
                 pnh.advertiseService("save", &ScanRegistrar::on_save, this)};
  }

 private:
  void on_mesh(const shape_msgs::Mesh::ConstPtr& msg) {
    try {
      auto mesh = std::make_shared<const Mesh>(from_mesh_msg(*msg, "mesh"));
      if (mesh->faces.empty()) throw Error("mesh", "has no triangles");
      std::lock_guard<std::mutex> lock(design_mutex_);
      design_ = std::move(mesh);
      diagnostics_.accepted("mesh", std::to_string(design_->faces.size()) + " facets as the design");
    } catch (const std::exception& e) {
      ROS_ERROR("scan_registrar: %s", e.what());
      diagnostics_.rejected("mesh", e.what());
    }
  }

  std::shared_ptr<const Mesh> design() {
    std::lock_guard<std::mutex> lock(design_mutex_);
    if (!design_) throw Error("design", "none yet: set ~design (an STL) or publish the part on `mesh`");
    return design_;
  }

  template <class Response, class Fn>
  bool answer(const char* what, Response& res, Fn&& fn) {
    return diagnostics_.answer("scan_registrar", what, res, std::forward<Fn>(fn));
  }

  bool on_start(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return answer("start", res, [&] { return session_.start(); });
  }
  bool on_reset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return answer("reset", res, [&] { return session_.reset(); });
  }
  bool on_add_view(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return answer("add_view", res, [&] { return session_.add_view(view_timeout_); });
  }

  bool on_finish(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return answer("finish", res, [&] {
      scan::FusionReport report;
      const PointCloud fused = session_.finish(fusion_, report);
      fused_pub_.publish(to_cloud_msg(fused, session_.fixed_frame()));
      return fusion_summary(report, session_.views(), session_.fixed_frame());
    });
  }

  bool on_register(RegisterScan::Request& req, RegisterScan::Response& res) {
    return answer("register", res, [&] {
      const PointCloud cloud = session_.cloud_named(req.scan);
      const scan::RegistrationResult r = scan::register_design(*design(), cloud, registration_);
      fill_response(r, session_.fixed_frame(), workpiece_frame_, res);
      if (r.ambiguous && !req.accept_ambiguous)
        throw Error("register", "the pose is ambiguous (" + r.ambiguity + "): nothing published; set "
                                "accept_ambiguous to publish the best pose anyway");
      publish_deviations(scan::inspect_registered(*design(), transformed_points(rigid_inverse(r.transform),
                                                                                 cloud.points), inspection(0)),
                         0);
      if (!req.dry_run) tf_broadcaster_.sendTransform(res.transform);
      return registration_summary(r, req.dry_run);
    });
  }

  bool on_inspect(InspectScan::Request& req, InspectScan::Response& res) {
    return answer("inspect", res, [&] {
      const double tolerance = req.tolerance > 0 ? to_mm(req.tolerance) : tolerance_;
      const PointCloud cloud = session_.cloud_named(req.scan);
      scan::InspectionReport r;
      if (req.use_workpiece_frame) {
        const Eigen::Matrix4d t = to_mm_pose(
            wait_for_transform(tf_, workpiece_frame_, session_.fixed_frame(), ::ros::Time(0), 1.0, "inspect"));
        r = scan::inspect_registered(*design(), transformed_points(t, cloud.points), inspection(tolerance));
      } else {
        r = scan::inspect(*design(), cloud, inspection(tolerance));
      }
      fill_response(r, tolerance, req.use_workpiece_frame, res);
      publish_deviations(r, tolerance);
      if (!req.stock_out.empty()) write_cloud(req.stock_out, PointCloud{r.points, {}}, Units::Metre);
      return inspection_summary(r);
    });
  }

  bool on_save(SaveScan::Request& req, SaveScan::Response& res) {
    return answer("save", res, [&] {
      if (req.path.empty()) throw Error("save", "no path given");
      PointCloud cloud = session_.cloud_named(req.scan);
      const std::string frame = req.frame.empty() ? workpiece_frame_ : req.frame;
      transform_points(to_mm_pose(wait_for_transform(tf_, frame, session_.fixed_frame(), ::ros::Time(0), 1.0, "save")),
                       cloud.points);
      write_cloud(req.path, cloud, Units::Metre);
      res.points = static_cast<uint32_t>(cloud.points.size());
      return std::to_string(cloud.points.size()) + " points in '" + frame + "' written to " + req.path;
    });
  }

  scan::InspectionOptions inspection(double tolerance) const {
    scan::InspectionOptions o;
    o.tolerance = tolerance > 0 ? tolerance : tolerance_;
    o.registration = registration_;
    return o;
  }

  void publish_deviations(const scan::InspectionReport& r, double tolerance) {
    std_msgs::Header header;
    header.frame_id = workpiece_frame_;
    header.stamp = ::ros::Time::now();
    markers_pub_.publish(deviation_markers(r, tolerance > 0 ? tolerance : tolerance_, header));
  }

  const std::string workpiece_frame_;
  const double view_timeout_, tolerance_;
  tf2_ros::Buffer tf_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::StaticTransformBroadcaster tf_broadcaster_;
  ScanSession session_;
  InputDiagnostics diagnostics_;
  scan::FusionOptions fusion_;
  scan::RegistrationOptions registration_;
  std::mutex design_mutex_;
  std::shared_ptr<const Mesh> design_;
  ::ros::Publisher fused_pub_, markers_pub_;
  ::ros::Subscriber cloud_sub_, mesh_sub_;
  std::vector<::ros::ServiceServer> services_;
};

}  // namespace
}  // namespace rosmill::edge

int main(int argc, char** argv) {
  // Three threads: clouds keep arriving while add_view waits for the next one, and a registration runs meanwhile.
  return rosmill::edge::run_node<rosmill::edge::ScanRegistrar>(argc, argv, "scan_registrar", 3);
}
