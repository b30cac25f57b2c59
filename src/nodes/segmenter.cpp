// segmenter: segments the part for machining (Lefebvre & Lauwers). On every mesh (`mesh`, from stl_loader) it runs
// phase 1
// (sharp-edge surface flooding and recombination, kept per mesh) and phase 2 for the current setup, and publishes
// the msg::Segmentation latched on `segmentation` and the coloured patches on `segmentation_markers`. The
// `set_setup` service re-runs only phase 2 for another setup.
#include <ros/ros.h>
#include <shape_msgs/Mesh.h>

#include <memory>

#include "rosmill/SetSetup.h"
#include "rosmill/error.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/input_diagnostics.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/segmentation_msg.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/segment/setup_segmentation.hpp"

namespace rosmill::edge {
namespace {

// A mesh and its phase 1 results, which refer to it by address: built in place and never moved.
struct SegmentedPart {
  Mesh mesh;
  segment::SurfacePatches patches;
  std::unique_ptr<segment::EgiSet> egis;
};

class Segmenter {
 public:
  Segmenter(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh)
      : frame_id_(string_param(pnh, "frame_id", "workpiece")),
        max_angle_deg_(double_param(pnh, "max_angle_deg", 90.0, 1.0, 180.0)),
        diagnostics_(nh) {
    options_.threshold = double_param(pnh, "normal_threshold", options_.threshold, 1e-6, 2.0);
    options_.small.min_area_fraction =
        double_param(pnh, "min_area_fraction", options_.small.min_area_fraction, 0.0, 0.5);
    const std::string setup = string_param(pnh, "setup", "+Z");
    filter_ = segment::setup_filter_of(setup, Vec3::UnitZ(), max_angle_deg_, "parameter " + pnh.resolveName("setup"));
    segmentation_pub_ = nh.advertise<msg::Segmentation>("segmentation", 1, true);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("segmentation_markers", 1, true);
    mesh_sub_ = nh.subscribe("mesh", 1, &Segmenter::on_mesh, this);
    service_ = nh.advertiseService("set_setup", &Segmenter::on_set_setup, this);
  }

 private:
  void on_mesh(const shape_msgs::Mesh::ConstPtr& msg) {
    try {
      const ::ros::WallTime t0 = ::ros::WallTime::now();
      auto part = std::make_unique<SegmentedPart>();
      part->mesh = from_mesh_msg(*msg, "mesh");
      if (part->mesh.faces.empty()) throw Error("mesh", "has no triangles");
      part->patches = segment::segment_surface(part->mesh, options_);
      part->egis = std::make_unique<segment::EgiSet>(part->patches);
      part_ = std::move(part);
      ROS_INFO("segmenter: %zu facets, %zu surface patches in %.3f s", part_->mesh.faces.size(),
               part_->patches.count(), (::ros::WallTime::now() - t0).toSec());
      publish();
      diagnostics_.accepted("mesh", std::to_string(part_->mesh.faces.size()) + " facets, " +
                                        std::to_string(part_->patches.count()) + " surface patches");
    } catch (const std::exception& e) {
      ROS_ERROR("segmenter: %s", e.what());
      diagnostics_.rejected("mesh", e.what());
    }
  }

  // Phase 2 for the current filter, published; returns it for the service's reply.
  segment::SetupSegmentation publish() {
    const ::ros::WallTime t0 = ::ros::WallTime::now();
    segment::SetupSegmentation seg = segment::segment_setup(*part_->egis, filter_);
    std_msgs::Header header;
    header.frame_id = frame_id_;
    header.stamp = ::ros::Time::now();
    segmentation_pub_.publish(to_segmentation_msg(seg, filter_.name, header));
    marker_pub_.publish(segmentation_markers(seg, header));
    ROS_INFO("segmenter: setup %s: %zu patches, %.1f%% of the area reachable, in %.3f s", filter_.name.c_str(),
             seg.count(), 100.0 * seg.reachable_fraction(), (::ros::WallTime::now() - t0).toSec());
    return seg;
  }

  bool on_set_setup(SetSetup::Request& req, SetSetup::Response& res) {
    try {
      const double max_angle_deg = req.max_angle == 0.0 ? max_angle_deg_ : max_angle_in_degrees(req.max_angle);
      filter_ = segment::setup_filter_of(req.setup, from_direction_msg(req.direction), max_angle_deg,
                                req.setup.empty() ? "direction" : "setup");
      res.success = true;
      if (!part_) {
        res.message = "setup " + filter_.name + " selected; no mesh yet: it applies to the next one";
        return true;
      }
      const segment::SetupSegmentation seg = publish();
      res.patches = seg.count();
      for (const segment::Segment& s : seg.segments()) res.reachable_patches += s.reachable ? 1 : 0;
      res.reachable_fraction = seg.reachable_fraction();
      res.message = "setup " + filter_.name + ": " + std::to_string(res.patches) + " patches";
      diagnostics_.accepted("set_setup request", res.message);
    } catch (const std::exception& e) {  // the setup in force stays
      res.success = false;
      res.message = e.what();
      ROS_WARN("segmenter: set_setup: %s", e.what());
      diagnostics_.rejected("set_setup request", e.what());
    }
    return true;
  }

  // The request's max_angle (radians) in degrees, in the range of the max_angle_deg parameter.
  static double max_angle_in_degrees(double radians) {
    constexpr double kMin = 1.0 * M_PI / 180.0;
    if (!(radians >= kMin && radians <= M_PI))
      throw Error("max_angle", "must be between " + std::to_string(kMin) + " and " + std::to_string(M_PI) +
                                   " rad (1 to 180 degrees; 0: the node's max_angle_deg), got " +
                                   std::to_string(radians) + " rad");
    return radians * 180.0 / M_PI;
  }

  std::string frame_id_;
  double max_angle_deg_;
  segment::SegmentOptions options_;
  segment::SetupFilter filter_;
  std::unique_ptr<SegmentedPart> part_;
  InputDiagnostics diagnostics_;
  ::ros::Publisher segmentation_pub_, marker_pub_;
  ::ros::Subscriber mesh_sub_;
  ::ros::ServiceServer service_;
};

}  // namespace
}  // namespace rosmill::edge

int main(int argc, char** argv) {
  // One thread: a mesh and a setup change never run at the same time.
  return rosmill::edge::run_node<rosmill::edge::Segmenter>(argc, argv, "segmenter");
}
