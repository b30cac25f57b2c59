// segmenter: segments the part for machining (Lefebvre & Lauwers). On every mesh (`mesh`, from stl_loader) it runs
// phase 1
// (sharp-edge surface flooding and recombination, kept per mesh) and phase 2 for the current setup, and publishes
// the msg::Segmentation latched on `segmentation` and the coloured patches on `segmentation_markers`. The
// `set_setup` service re-runs only phase 2 for another setup, or with "auto" chooses the setups that reach the most
// of the part with the fewest (setups/setup_choice.hpp) for the tool `setup_tool` of `tool_table` (a spec such as
// ball:6 without a table), the face `held_face` (+Z, -Z, ...; empty: none) never machined.
#include <ros/ros.h>
#include <shape_msgs/Mesh.h>

#include <memory>
#include <optional>

#include "rosmill/SetSetup.h"
#include "rosmill/error.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/input_diagnostics.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/ros/segmentation_msg.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/ros/markers.hpp"
#include "rosmill/segment/setup_segmentation.hpp"
#include "rosmill/setups/setup_choice.hpp"

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
    const std::string table = string_param(pnh, "tool_table", "");
    if (!table.empty()) tools_ = read_tool_table(table);
    choice_.tool = resolve_tool(string_param(pnh, "setup_tool", table.empty() ? "ball:6" : "2"), tools_ ? &*tools_ : nullptr);
    const std::string held = string_param(pnh, "held_face", "");
    if (!held.empty()) choice_.held_face = named_setup(held, "parameter " + pnh.resolveName("held_face")).tool_axis;
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

  // Phase 2 for the current filter, published (with the facets coloured by the setups of a choice, when given);
  // returns it for the service's reply.
  segment::SetupSegmentation publish(const setups::SetupChoice* choice = nullptr) {
    const ::ros::WallTime t0 = ::ros::WallTime::now();
    segment::SetupSegmentation seg = segment::segment_setup(*part_->egis, filter_);
    std_msgs::Header header;
    header.frame_id = frame_id_;
    header.stamp = ::ros::Time::now();
    segmentation_pub_.publish(to_segmentation_msg(seg, filter_.name, header));
    visualization_msgs::MarkerArray markers = segmentation_markers(seg, header);
    if (choice)
      markers.markers.push_back(
          facets_by_setup_marker(part_->mesh, setups::facet_setups(*choice, part_->mesh.face_count()), header));
    marker_pub_.publish(markers);
    ROS_INFO("segmenter: setup %s: %zu patches, %.1f%% of the area reachable, in %.3f s", filter_.name.c_str(),
             seg.count(), 100.0 * seg.reachable_fraction(), (::ros::WallTime::now() - t0).toSec());
    return seg;
  }

  // "auto": the setups chosen for the part, the first one's segmentation, the facets coloured by setup.
  void choose(SetSetup::Response& res) {
    if (!part_) throw Error("setup auto", "no mesh yet: setups are chosen for a part");
    choice_.max_angle_deg = max_angle_deg_;
    const setups::SetupChoice c = setups::choose_setups(part_->mesh, part_->patches, choice_);
    if (c.setups.empty()) throw Error("setup auto", "no setup reaches the part");
    for (const setups::ChosenSetup& s : c.setups) {
      res.setups.push_back(s.name);
      res.setup_directions.push_back(to_direction_msg(s.direction));
      res.setup_areas.push_back(s.assigned_area * kMetrePerMm * kMetrePerMm);
    }
    res.unreachable_area = c.unreachable_area * kMetrePerMm * kMetrePerMm;
    filter_ = segment::setup_filter_of("", c.setups.front().direction, max_angle_deg_, "setup auto");
    filter_.name = c.setups.front().name;
    const segment::SetupSegmentation seg = publish(&c);
    res.patches = seg.count();
    res.reachable_fraction = seg.reachable_fraction();
    res.message = std::to_string(c.setups.size()) + " setups chosen for the " + choice_.tool.name + ", " +
                  std::to_string(c.unreachable_area) + " mm^2 of the part unmachined";
  }

  bool on_set_setup(SetSetup::Request& req, SetSetup::Response& res) {
    try {
      if (req.setup == "auto") {
        choose(res);
        res.success = true;
        diagnostics_.accepted("set_setup request", res.message);
        return true;
      }
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
  std::optional<ToolTable> tools_;
  setups::ChoiceOptions choice_;
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
