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
#include "rosmill/geometry/mesh_report.hpp"
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
  // Loads and publishes; returns the part's report for the reply. Throws Error on a bad file or unit. The part
  // stays welded triangles (what the message and the marker carry): the normals, areas and edge tables of a Mesh
  // are built by the nodes that plan on it, not here, where they would double the first load of a large part.
  MeshReport load(const std::string& path, const std::string& units, const std::string& frame) {
    const ::ros::WallTime t0 = ::ros::WallTime::now();
    IndexedTriangles part;
    const std::string prefix = "primitive:";
    StlReadOptions options;
    options.units = parse_units(units, "units");  // checked for primitives too: a wrong request is refused whole
    options.weld.tolerance = weld_tolerance_;
    if (path.rfind(prefix, 0) == 0) {
      Mesh primitive = make_primitive(path.substr(prefix.size()));  // the primitives are in millimetres
      part = {std::move(primitive.vertices), std::move(primitive.faces)};
    } else {
      part = read_stl_triangles(path, options);
    }
    if (part.faces.empty()) throw Error(path, "holds no triangles");
    if (frame != frame_id_)
      move(part, wait_for_transform(tf_buffer_, frame_id_, frame, ::ros::Time(0), tf_timeout_,
                                    "frame_id '" + frame + "'"));
    std_msgs::Header header;
    header.frame_id = frame_id_;
    header.stamp = ::ros::Time::now();
    const MeshReport r = report(part);  // checks the faces' indices: nothing is published for a part it refuses
    mesh_pub_.publish(to_mesh_msg(part));
    marker_pub_.publish(mesh_marker(part, header, "part", rgba(0.7f, 0.7f, 0.75f, 1.0f)));
    ROS_INFO("stl_loader: %s: %zu triangles, %zu vertices, in %.3f s", path.c_str(), r.triangles, r.vertices,
             (::ros::WallTime::now() - t0).toSec());
    diagnostics_.accepted("part", path + ": " + std::to_string(r.triangles) + " triangles");
    return r;
  }

  // Every vertex moved by `t` (metres on tf, millimetres in the part): a rigid motion keeps the welding.
  static void move(IndexedTriangles& part, const Eigen::Isometry3d& t) {
    const Vec3 shift = to_mm(1.0) * t.translation();
    for (Vec3& v : part.vertices) v = t.linear() * v + shift;
  }

  bool on_load(LoadMesh::Request& req, LoadMesh::Response& res) {
    try {
      const MeshReport r = load(req.path, req.units.empty() ? units_ : req.units,
                                req.frame_id.empty() ? frame_id_ : req.frame_id);
      res.success = true;
      res.triangles = r.triangles;
      res.closed = r.closed;
      res.bounds_min = to_point_msg(r.bbox.min);
      res.bounds_max = to_point_msg(r.bbox.max);
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
