#include "rosmill/ros/slices_msg.hpp"

#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/markers.hpp"

namespace rosmill::edge {

namespace {

constexpr double kSquareMetrePerSquareMm = kMetrePerMm * kMetrePerMm;

msg::Contour to_contour_msg(const core::Contour& c, double z) {
  msg::Contour m;
  m.points.reserve(c.points.size());
  for (const Vec2& p : c.points) m.points.push_back(to_point_msg(Vec3(p.x(), p.y(), z)));
  m.closed = c.closed;
  m.hole = c.hole;
  m.parent = c.parent;
  m.area = c.area * kSquareMetrePerSquareMm;
  return m;
}

std_msgs::ColorRGBA contour_colour(const core::Contour& c) {
  if (!c.closed) return rgba(1.0f, 0.15f, 0.15f);
  return c.hole ? rgba(1.0f, 0.6f, 0.1f) : rgba(0.2f, 0.55f, 1.0f);
}

// The contour's segments as pairs of points (LINE_LIST), the closing one included for a closed contour.
void add_segments(visualization_msgs::Marker& lines, const core::Contour& c, double z) {
  const size_t n = c.points.size();
  if (n < 2) return;
  const std_msgs::ColorRGBA colour = contour_colour(c);
  const size_t segments = c.closed ? n : n - 1;
  for (size_t i = 0; i < segments; ++i) {
    const Vec2& a = c.points[i];
    const Vec2& b = c.points[(i + 1) % n];
    lines.points.push_back(to_point_msg(Vec3(a.x(), a.y(), z)));
    lines.points.push_back(to_point_msg(Vec3(b.x(), b.y(), z)));
    lines.colors.push_back(colour);
    lines.colors.push_back(colour);
  }
}

}  // namespace

msg::Slices to_slices_msg(const std::vector<core::SliceLayer>& layers, double interval_mm,
                          const std_msgs::Header& header) {
  msg::Slices m;
  m.header = header;
  m.interval = to_metres(interval_mm);
  m.layers.resize(layers.size());
  for (size_t k = 0; k < layers.size(); ++k) {
    const core::SliceLayer& in = layers[k];
    msg::SliceLayer& out = m.layers[k];
    out.z = to_metres(in.z);
    out.flat_area = in.flat_area * kSquareMetrePerSquareMm;
    out.contours.reserve(in.contours.size());
    for (const core::Contour& c : in.contours) {
      out.contours.push_back(to_contour_msg(c, in.z));
      m.open_contours += c.closed ? 0 : 1;
    }
    m.contours += in.contours.size();
  }
  return m;
}

visualization_msgs::MarkerArray slice_markers(const std::vector<core::SliceLayer>& layers,
                                              const std_msgs::Header& header) {
  visualization_msgs::MarkerArray array;
  array.markers.push_back(delete_all_marker(header));
  for (size_t k = 0; k < layers.size(); ++k) {
    visualization_msgs::Marker m = base_marker(header, "slices", int(k), visualization_msgs::Marker::LINE_LIST);
    m.scale.x = 0.0003;  // line width, m
    m.color = rgba(1, 1, 1);
    for (const core::Contour& c : layers[k].contours) add_segments(m, c, layers[k].z);
    if (!m.points.empty()) array.markers.push_back(std::move(m));
  }
  return array;
}

}  // namespace rosmill::edge
