// stl_loader: reads an STL part (the `path` parameter at start-up, or the load_mesh service at any time) and
// publishes it latched as shape_msgs/Mesh on `mesh` (metres) and as a marker on `mesh_marker`, both in the
// pipeline's frame `frame_id` (the workpiece). shape_msgs/Mesh has no header, so a part whose coordinates are in
// another frame (load_mesh's frame_id) is moved into the pipeline's frame with tf2 before it is published: every
// node downstream (segmentation, slices, toolpaths) then sees it where it is. Loads accepted and refused are on
// /diagnostics.
// A path "primitive:<name>" loads a test primitive of the STL slicing paper (cube, cylinder, dome, cone, cavity).
#include <ros/ros.h>
#include <shape_msgs/Mesh.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/Marker.h>

#include "rosmill/LoadMesh.h"
#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/input_diagnostics.hpp"
#include "rosmill/ros/markers.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/transform_wait.hpp"

namespace rosmill::edge {
namespace {

class StlLoader {
 public:
  StlLoader(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh)
      : frame_id_(string_param(pnh, "frame_id", "workpiece")),
        units_(string_param(pnh, "units", "mm")),
        weld_tolerance_(double_param(pnh, "weld_tolerance", 0.0, 0.0, 1.0)),
        tf_timeout_(double_param(pnh, "tf_timeout", 1.0, 0.0, 30.0)),
        tf_listener_(tf_buffer_),
        diagnostics_(nh) {
    parse_units(units_, "parameter units");  // validate now, not at the first load
    mesh_pub_ = nh.advertise<shape_msgs::Mesh>("mesh", 1, true);
    marker_pub_ = nh.advertise<visualization_msgs::Marker>("mesh_marker", 1, true);
    service_ = nh.advertiseService("load_mesh", &StlLoader::on_load, this);
    const std::string path = string_param(pnh, "path", "");
    if (path.empty()) return;
    // A bad start-up file is reported; the node stays up so that load_mesh can load another one.
    try {
      load(path, units_, frame_id_);
    } catch (const std::exception& e) {
      ROS_ERROR("stl_loader: parameter %s: %s", pnh.resolveName("path").c_str(), e.what());
      diagnostics_.rejected("part", e.what());
    }
  }

 private:
  // Loads and publishes; returns the mesh for the reply. Throws Error on a bad file or unit.
  Mesh load(const std::string& path, const std::string& units, const std::string& frame) {
    const ::ros::WallTime t0 = ::ros::WallTime::now();
    Mesh mesh;
    const std::string prefix = "primitive:";
    StlReadOptions options;
    options.units = parse_units(units, "units");  // checked for primitives too: a wrong request is refused whole
    options.weld.tolerance = weld_tolerance_;
    if (path.rfind(prefix, 0) == 0)
      mesh = make_primitive(path.substr(prefix.size()));  // the primitives are in millimetres
    else
      mesh = read_stl(path, options);
    if (mesh.faces.empty()) throw Error(path, "holds no triangles");
    if (frame != frame_id_)
      mesh = transformed(mesh, wait_for_transform(tf_buffer_, frame_id_, frame, ::ros::Time(0), tf_timeout_,
                                                  "frame_id '" + frame + "'"));
    std_msgs::Header header;
    header.frame_id = frame_id_;
    header.stamp = ::ros::Time::now();
    mesh_pub_.publish(to_mesh_msg(mesh));
    marker_pub_.publish(mesh_marker(mesh, header, "part", rgba(0.7f, 0.7f, 0.75f, 1.0f)));
    ROS_INFO("stl_loader: %s: %zu triangles, %zu vertices, in %.3f s", path.c_str(), mesh.faces.size(),
             mesh.vertices.size(), (::ros::WallTime::now() - t0).toSec());
    diagnostics_.accepted("part", path + ": " + std::to_string(mesh.faces.size()) + " triangles");
    return mesh;
  }

  // The mesh with every vertex moved by `t` (metres on tf, millimetres in the mesh).
  static Mesh transformed(const Mesh& mesh, const Eigen::Isometry3d& t) {
    std::vector<Vec3> corners;
    corners.reserve(3 * mesh.faces.size());
    const Vec3 shift = to_mm(1.0) * t.translation();
    for (const auto& face : mesh.faces)
      for (int i = 0; i < 3; ++i) corners.push_back(t.linear() * mesh.vertices[face[i]] + shift);
    return build_mesh(corners);
  }

  bool on_load(LoadMesh::Request& req, LoadMesh::Response& res) {
    try {
      const Mesh mesh = load(req.path, req.units.empty() ? units_ : req.units,
                             req.frame_id.empty() ? frame_id_ : req.frame_id);
      res.success = true;
      res.triangles = mesh.faces.size();
      res.closed = mesh.closed();
      res.bounds_min = to_point_msg(mesh.bbox.min);
      res.bounds_max = to_point_msg(mesh.bbox.max);
      res.message = "loaded " + std::to_string(res.triangles) + " triangles";
    } catch (const std::exception& e) {  // rosmill::Error and allocation failures alike: the node stays up
      res.success = false;
      res.message = e.what();
      ROS_WARN("stl_loader: %s", e.what());
      diagnostics_.rejected("part", e.what());
    }
    return true;
  }

  std::string frame_id_;
  std::string units_;
  double weld_tolerance_, tf_timeout_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  InputDiagnostics diagnostics_;
  ::ros::Publisher mesh_pub_, marker_pub_;
  ::ros::ServiceServer service_;
};

}  // namespace
}  // namespace rosmill::edge

int main(int argc, char** argv) {
  return rosmill::edge::run_node<rosmill::edge::StlLoader>(argc, argv, "stl_loader");
}
