// slicer: cuts every mesh (`mesh`, from stl_loader) by planes z = const (the STL slicing paper) and publishes the
// contours
// latched on `slices` (msg::Slices) and as lines on `slice_markers`. The planes are every `interval` mm from the
// mesh's lowest point, or `layers` evenly spaced planes when that parameter is above 0.
#include <ros/ros.h>
#include <shape_msgs/Mesh.h>

#include "rosmill/error.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/input_diagnostics.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/slices_msg.hpp"
#include "rosmill/slice/slicer.hpp"

namespace rosmill::edge {
namespace {

class Slicer {
 public:
  Slicer(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh)
      : frame_id_(string_param(pnh, "frame_id", "workpiece")),
        interval_(double_param(pnh, "interval", 2.0, 1e-3, 1e4)),
        layers_(int_param(pnh, "layers", 0, 0, 100000)),
        diagnostics_(nh) {
    slices_pub_ = nh.advertise<msg::Slices>("slices", 1, true);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("slice_markers", 1, true);
    mesh_sub_ = nh.subscribe("mesh", 1, &Slicer::on_mesh, this);
  }

 private:
  void on_mesh(const shape_msgs::Mesh::ConstPtr& msg) {
    try {
      const ::ros::WallTime t0 = ::ros::WallTime::now();
      const Mesh mesh = from_mesh_msg(*msg, "mesh");
      if (mesh.faces.empty()) throw Error("mesh", "has no triangles");
      const std::vector<double> planes =
          layers_ > 0 ? planes_by_count(mesh, layers_, "parameter layers") : planes_by_step(mesh, interval_, "parameter interval");
      const std::vector<core::SliceLayer> layers = slice_mesh(mesh, planes);
      std_msgs::Header header;
      header.frame_id = frame_id_;
      header.stamp = ::ros::Time::now();
      const double spacing = layers_ > 0 ? (mesh.bbox.max.z() - mesh.bbox.min.z()) / (layers_ + 1) : interval_;
      slices_pub_.publish(to_slices_msg(layers, spacing, header));
      marker_pub_.publish(slice_markers(layers, header));
      const SliceSummary sum = summarize(layers);
      ROS_INFO("slicer: %zu layers, %zu contours (%zu open), %zu points in %.3f s", sum.layers, sum.contours,
               sum.open_contours, sum.points, (::ros::WallTime::now() - t0).toSec());
      diagnostics_.accepted("mesh", std::to_string(sum.layers) + " layers, " + std::to_string(sum.contours) +
                                        " contours");
    } catch (const std::exception& e) {
      ROS_ERROR("slicer: %s", e.what());
      diagnostics_.rejected("mesh", e.what());
    }
  }

  std::string frame_id_;
  double interval_;
  int layers_;
  InputDiagnostics diagnostics_;
  ::ros::Publisher slices_pub_, marker_pub_;
  ::ros::Subscriber mesh_sub_;
};

}  // namespace
}  // namespace rosmill::edge

int main(int argc, char** argv) { return rosmill::edge::run_node<rosmill::edge::Slicer>(argc, argv, "slicer"); }
