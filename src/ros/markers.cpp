#include "rosmill/ros/markers.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/ros/convert.hpp"

namespace rosmill::edge {

std_msgs::ColorRGBA rgba(float r, float g, float b, float a) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

std_msgs::ColorRGBA move_colour(MoveType t) {
  switch (t) {
    case MoveType::Rapid: return rgba(1.0f, 0.1f, 0.1f);
    case MoveType::Feed: return rgba(0.1f, 0.9f, 0.1f);
    case MoveType::Plunge: return rgba(0.2f, 0.3f, 1.0f);
  }
  return rgba(1, 1, 1);
}

std_msgs::ColorRGBA label_colour(uint32_t label) {
  // Hue steps of the golden ratio keep neighbouring labels far apart on the colour wheel.
  const double h = std::fmod(0.1 + label * 0.618033988749895, 1.0) * 6.0;
  const double x = 1.0 - std::fabs(std::fmod(h, 2.0) - 1.0);
  const float s = 0.85f, v = 0.95f, c = s * v, m = v - c;
  float r = 0, g = 0, b = 0;
  switch (int(h)) {
    case 0: r = c, g = c * x; break;
    case 1: r = c * x, g = c; break;
    case 2: g = c, b = c * x; break;
    case 3: g = c * x, b = c; break;
    case 4: r = c * x, b = c; break;
    default: r = c, b = c * x; break;
  }
  return rgba(r + m, g + m, b + m);
}

visualization_msgs::Marker base_marker(const std_msgs::Header& header, const std::string& ns, int id, int type) {
  visualization_msgs::Marker m;
  m.header = header;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = 1.0;
  return m;
}

double text_width_mm(double height_mm, size_t chars) {
  return 0.6 * height_mm * static_cast<double>(chars);  // rviz's sans face: no glyph is wider than 0.6 of the height
}

visualization_msgs::Marker text_from_left(const std_msgs::Header& header, const std::string& ns, int id,
                                          const Vec3& left, const std::string& text, double height_mm, size_t chars) {
  visualization_msgs::Marker m = base_marker(header, ns, id, visualization_msgs::Marker::TEXT_VIEW_FACING);
  const size_t first_line = std::min(text.find('\n'), text.size());
  m.text = text;
  if (first_line < chars) m.text.insert(first_line, chars - first_line, ' ');
  m.pose.position = to_point_msg(left + Vec3(0.5 * text_width_mm(height_mm, chars), 0, 0));
  m.scale.z = to_metres(height_mm);
  return m;
}

void add_facet(visualization_msgs::Marker& triangles, const Mesh& mesh, size_t f) {
  if (mesh.areas[f] <= 0) return;
  for (int i = 0; i < 3; ++i) triangles.points.push_back(to_point_msg(mesh.corner(f, i)));
}

visualization_msgs::Marker delete_all_marker(const std_msgs::Header& header) {
  visualization_msgs::Marker clear;
  clear.header = header;
  clear.action = visualization_msgs::Marker::DELETEALL;
  return clear;
}

std_msgs::ColorRGBA setup_colour(size_t setup) { return label_colour(static_cast<uint32_t>(setup)); }

visualization_msgs::Marker facets_by_setup_marker(const Mesh& part, const std::vector<int>& facet_setup,
                                                  const std_msgs::Header& header) {
  visualization_msgs::Marker m = base_marker(header, "setups", 0, visualization_msgs::Marker::TRIANGLE_LIST);
  m.color = rgba(1, 1, 1);
  for (size_t f = 0; f < part.faces.size() && f < facet_setup.size(); ++f) {
    add_facet(m, part, f);
    m.colors.resize(m.points.size(), facet_setup[f] < 0 ? rgba(0.6f, 0.6f, 0.6f, 0.8f) : setup_colour(facet_setup[f]));
  }
  return m;
}

visualization_msgs::Marker mesh_marker(const IndexedTriangles& part, const std_msgs::Header& header,
                                       const std::string& ns, const std_msgs::ColorRGBA& colour) {
  visualization_msgs::Marker m = base_marker(header, ns, 0, visualization_msgs::Marker::TRIANGLE_LIST);
  m.color = colour;
  m.points.reserve(part.faces.size() * 3);
  for (const Mesh::Face& face : part.faces)
    if (face_cross(part.vertices, face).norm() > 0.0)  // a degenerate facet has nothing to draw
      for (uint32_t v : face) m.points.push_back(to_point_msg(part.vertices[v]));
  return m;
}

namespace {

void add_vertex(visualization_msgs::Marker& strip, const Vec3& p, const std_msgs::ColorRGBA& c) {
  strip.points.push_back(to_point_msg(p));
  strip.colors.push_back(c);
}

visualization_msgs::Marker pass_marker(const core::ToolpathPass& pass, Vec3 at, const SetupFrame& setup,
                                       const std_msgs::Header& header, const std::string& ns,
                                       const std_msgs::ColorRGBA* cut_colour) {
  visualization_msgs::Marker m = base_marker(header, ns, 0, visualization_msgs::Marker::LINE_STRIP);
  m.scale.x = 0.0004;  // line width, m
  m.color = rgba(1, 1, 1);
  m.points.reserve(pass.moves.size() + 8);
  m.colors.reserve(pass.moves.size() + 8);
  bool first = true;
  MoveType current = MoveType::Feed;
  for (const Move& move : pass.moves) {
    const std_msgs::ColorRGBA c = !cut_colour                      ? move_colour(move.type)
                                  : move.type == MoveType::Rapid ? rgba(0.55f, 0.55f, 0.55f, 0.6f)
                                                                 : *cut_colour;
    if (first || move.type != current) add_vertex(m, setup.to_workpiece_frame(at), c);  // colour switch point
    add_vertex(m, setup.to_workpiece_frame(move.to), c);
    at = move.to;
    current = move.type;
    first = false;
  }
  return m;
}

// A multi-axis pass's tool axes: a LINE_LIST of short strokes from the cutter location up its tool axis, one every
// `spacing` mm of the path (more where the pass is long, at most about 2,000), so that the tilt reads along the path.
visualization_msgs::Marker axes_marker(const core::ToolpathPass& pass, const SetupFrame& setup,
                                       const std_msgs::Header& header, const std::string& ns, double length) {
  visualization_msgs::Marker m = base_marker(header, ns, 0, visualization_msgs::Marker::LINE_LIST);
  m.scale.x = 0.0003;  // line width, m
  m.color = rgba(0.3f, 0.9f, 1.0f, 0.9f);
  double path = 0;
  for (size_t k = 1; k < pass.moves.size(); ++k) path += (pass.moves[k].to - pass.moves[k - 1].to).norm();
  const double spacing = std::max(2.0, path / 2000.0);
  double since = INFINITY;  // the first move gets a stroke
  for (size_t k = 0; k < pass.moves.size() && k < pass.axes.size(); ++k) {
    if (k > 0) since += (pass.moves[k].to - pass.moves[k - 1].to).norm();
    if (since < spacing || pass.moves[k].type == MoveType::Rapid) continue;
    since = 0;
    m.points.push_back(to_point_msg(setup.to_workpiece_frame(pass.moves[k].to)));
    m.points.push_back(to_point_msg(setup.to_workpiece_frame(pass.moves[k].to + length * pass.axes[k])));
  }
  return m;
}

visualization_msgs::Marker tool_marker(const core::Toolpath& tp, const SetupFrame& setup,
                                       const std_msgs::Header& header, const std::string& ns) {
  visualization_msgs::Marker m = base_marker(header, ns, 0, visualization_msgs::Marker::CYLINDER);
  const double length = tp.tool.cutter.flute_length > 0 ? tp.tool.cutter.flute_length : 4 * tp.tool.cutter.diameter;
  // The cylinder's centre sits half a flute above the tip; its axis is the setup's tool axis.
  const Vec3 centre = setup.to_workpiece_frame(tp.start + Vec3(0, 0, 0.5 * length));
  m.pose.position = to_point_msg(centre);
  const Eigen::Quaterniond q = setup.rotation().conjugate();
  m.pose.orientation.x = q.x();
  m.pose.orientation.y = q.y();
  m.pose.orientation.z = q.z();
  m.pose.orientation.w = q.w();
  m.scale.x = m.scale.y = to_metres(tp.tool.cutter.diameter);
  m.scale.z = to_metres(length);
  m.color = rgba(0.8f, 0.8f, 0.2f, 0.8f);
  return m;
}

}  // namespace

visualization_msgs::MarkerArray toolpath_markers(const Job& job, const SetupFrame& setup,
                                                 const std_msgs::Header& header, const std::string& ns_prefix,
                                                 const std_msgs::ColorRGBA* cut_colour) {
  visualization_msgs::MarkerArray array;
  array.markers.push_back(delete_all_marker(header));
  for (size_t t = 0; t < job.size(); ++t) {
    const core::Toolpath& tp = job[t];
    const std::string prefix = ns_prefix + "toolpath" + std::to_string(t) + "/";
    Vec3 at = tp.start;
    for (size_t p = 0; p < tp.passes.size(); ++p) {
      const core::ToolpathPass& pass = tp.passes[p];
      if (pass.moves.empty()) continue;
      const std::string name = pass.name.empty() ? "pass" + std::to_string(p) : pass.name;
      array.markers.push_back(
          pass_marker(pass, at, setup, header, prefix + std::to_string(p) + "_" + name, cut_colour));
      if (!pass.axes.empty())
        array.markers.push_back(axes_marker(pass, setup, header, prefix + std::to_string(p) + "_" + name + "/axes",
                                            std::max(5.0, 2.0 * tp.tool.cutter.diameter)));
      at = pass.moves.back().to;
    }
    array.markers.push_back(tool_marker(tp, setup, header, prefix + "tool"));
  }
  return array;
}

}  // namespace rosmill::edge
