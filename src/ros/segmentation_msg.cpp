#include "rosmill/ros/segmentation_msg.hpp"

#include <cmath>

#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/markers.hpp"

namespace rosmill::edge {

namespace {

constexpr double kSquareMetrePerSquareMm = kMetrePerMm * kMetrePerMm;

// The direction a setup is known by: the tool axis (3-axis), the rotary axis (4-axis), none (5-axis).
Vec3 setup_axis(const segment::SetupFilter& f) {
  return f.kind == segment::SetupFilter::Kind::FiveAxis ? Vec3::Zero() : f.axis;
}

}  // namespace

msg::Segmentation to_segmentation_msg(const segment::SetupSegmentation& seg, const std::string& setup_name,
                                    const std_msgs::Header& header) {
  msg::Segmentation m;
  m.header = header;
  m.setup = setup_name;
  m.tool_axis = to_direction_msg(setup_axis(seg.filter()));
  m.max_angle = seg.filter().max_angle_deg * M_PI / 180.0;
  m.surface_patches = seg.patches().count();
  m.reachable_fraction = seg.reachable_fraction();
  m.facet_labels = seg.labels();
  m.patches.resize(seg.count());
  for (size_t i = 0; i < seg.count(); ++i) {
    const segment::Segment& s = seg.segments()[i];
    msg::Patch& p = m.patches[i];
    p.label = i;
    p.surface_patch = s.patch;
    p.facet_count = s.shape.facet_count;
    p.area = s.shape.area * kSquareMetrePerSquareMm;
    p.reachable_area = s.reachable_area * kSquareMetrePerSquareMm;
    p.normal = to_direction_msg(s.shape.normal);
    p.reachable = s.reachable;
  }
  return m;
}

visualization_msgs::MarkerArray segmentation_markers(const segment::SetupSegmentation& seg,
                                                     const std_msgs::Header& header) {
  const Mesh& mesh = seg.patches().mesh();
  visualization_msgs::MarkerArray array;
  array.markers.push_back(delete_all_marker(header));
  const uint32_t* order = seg.facet_order().data();
  for (size_t i = 0; i < seg.count(); ++i) {
    const segment::Segment& s = seg.segments()[i];
    visualization_msgs::Marker m = base_marker(header, s.reachable ? "reachable" : "unreachable", int(i),
                                               visualization_msgs::Marker::TRIANGLE_LIST);
    m.color = s.reachable ? label_colour(uint32_t(i)) : rgba(0.25f, 0.25f, 0.28f, 0.6f);
    m.points.reserve(size_t(s.shape.facet_count) * 3);
    for (uint32_t k = 0; k < s.shape.facet_count; ++k) add_facet(m, mesh, order[s.shape.first_facet + k]);
    if (!m.points.empty()) array.markers.push_back(std::move(m));
  }
  return array;
}

}  // namespace rosmill::edge
