#include "rosmill/ros/job_markers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rosmill/ros/convert.hpp"
#include "rosmill/fixture/fixture.hpp"
#include "rosmill/ros/markers.hpp"
#include "rosmill/stock/material_left.hpp"
#include "rosmill/stock/stock_surface.hpp"

namespace rosmill::edge {
namespace {

constexpr double kTolerance = 0.05;  // mm: within this of the design the part is done (green)
constexpr double kFull = 2.0;        // mm: this much left and more is red

constexpr double kLegendHeight = 4.0;  // mm: the legend's text height
constexpr double kLegendGap = 10.0;    // mm between the stock and the legend
constexpr size_t kLegendChars = 36;    // the longest line's characters: every line is padded to it

visualization_msgs::Marker legend_line(const std_msgs::Header& header, int id, const Vec3& left,
                                       const std::string& text, const std_msgs::ColorRGBA& colour) {
  visualization_msgs::Marker m = text_from_left(header, "legend", id, left, text, kLegendHeight, kLegendChars);
  m.color = colour;
  return m;
}

}  // namespace

std_msgs::ColorRGBA material_left_colour(float left, double tolerance, double full) {
  if (std::isnan(left)) return rgba(0.6f, 0.6f, 0.6f, 0.5f);
  if (left < -tolerance) return rgba(1.0f, 0.0f, 1.0f);
  if (left <= tolerance) return rgba(0.1f, 0.8f, 0.1f);
  const float t = static_cast<float>(std::min(1.0, (left - tolerance) / (full - tolerance)));
  // green -> yellow over the first half, yellow -> red over the second
  return t < 0.5f ? rgba(2 * t, 0.8f + 0.2f * 2 * t, 0.1f) : rgba(1.0f, 2 * (1 - t), 0.1f);
}

namespace {

// The fixture's colour: its fill faint enough that the part and the toolpaths inside the vise stay in view through
// the jaws of every setup at once (a job's five vises, turned into the workpiece frame, surround the part: through
// six layers this fill still lets half the light through); its edges, stronger, show where it stands.
constexpr float kFixtureFillAlpha = 0.1f;
constexpr float kFixtureEdgeAlpha = 0.5f;
constexpr double kFixtureEdgeWidth = 0.0003;  // m

std_msgs::ColorRGBA fixture_colour(float alpha) { return rgba(0.62f, 0.44f, 0.27f, alpha); }

// A setup's fixture, its boxes turned back from the setup's frame into the workpiece's: a faint fill (id 0).
visualization_msgs::Marker fixture_fill(const job::SetupReport& s, const std_msgs::Header& header, const std::string& ns) {
  visualization_msgs::Marker m = base_marker(header, ns, 0, visualization_msgs::Marker::TRIANGLE_LIST);
  m.color = fixture_colour(kFixtureFillAlpha);
  for (const Vec3& corner : fixture::fixture_corners(s.fixture))
    m.points.push_back(to_point_msg(s.frame.to_workpiece_frame(corner)));
  return m;
}

// The same boxes' twelve edges each (id 1), a LINE_LIST.
visualization_msgs::Marker fixture_edges(const job::SetupReport& s, const std_msgs::Header& header, const std::string& ns) {
  visualization_msgs::Marker m = base_marker(header, ns, 1, visualization_msgs::Marker::LINE_LIST);
  m.color = fixture_colour(kFixtureEdgeAlpha);
  m.scale.x = kFixtureEdgeWidth;
  for (const fixture::FixtureBox& b : s.fixture.boxes) {
    // Corner k has x from bit 0, y from bit 1, z from bit 2 (min or max); an edge joins two that differ by one bit.
    auto corner = [&](int k) {
      return Vec3(k & 1 ? b.box.max.x() : b.box.min.x(), k & 2 ? b.box.max.y() : b.box.min.y(),
                  k & 4 ? b.box.max.z() : b.box.min.z());
    };
    for (int k = 0; k < 8; ++k)
      for (int bit = 1; bit < 8; bit <<= 1) {
        if (k & bit) continue;
        m.points.push_back(to_point_msg(s.frame.to_workpiece_frame(corner(k))));
        m.points.push_back(to_point_msg(s.frame.to_workpiece_frame(corner(k | bit))));
      }
  }
  return m;
}

}  // namespace

std::string operation_namespace(const job::OperationView& view) {
  return std::to_string(view.index + 1) + "_" + view.report.name + "/";
}

const visualization_msgs::MarkerArray& JobMarkers::add_operation(const job::OperationView& view) {
  if (toolpaths_.markers.empty()) toolpaths_.markers.push_back(delete_all_marker(header_));
  const size_t setup = view.report.setup_index;
  if (setup + 1 > size_t(setups_seen_)) {
    setups_seen_ = int(setup) + 1;
    if (!view.setup.fixture.empty()) {
      const std::string ns = "fixture/" + std::to_string(setup + 1) + "_" + view.setup.name;
      toolpaths_.markers.push_back(fixture_fill(view.setup, header_, ns));
      toolpaths_.markers.push_back(fixture_edges(view.setup, header_, ns));
    }
    if (setup == 0 && view.facet_setup.size() == view.part.faces.size())
      toolpaths_.markers.push_back(facets_by_setup_marker(view.part, view.facet_setup, header_));
  }
  const std_msgs::ColorRGBA colour = setup_colour(setup);
  const visualization_msgs::MarkerArray op = toolpath_markers(view.toolpaths, view.setup.frame, header_,
                                                              operation_namespace(view), &colour);
  toolpaths_.markers.insert(toolpaths_.markers.end(), op.markers.begin() + 1, op.markers.end());  // not its DELETEALL
  return toolpaths_;
}

const visualization_msgs::MarkerArray& JobMarkers::add_surface(const Mesh& part, const job::SurfaceAccount& surface) {
  if (toolpaths_.markers.empty()) toolpaths_.markers.push_back(delete_all_marker(header_));
  visualization_msgs::Marker m = base_marker(header_, "surface", 0, visualization_msgs::Marker::TRIANGLE_LIST);
  m.color = rgba(1, 1, 1);
  int note = 0;
  for (const job::FaceLeft& face : surface.faces) {
    const std_msgs::ColorRGBA colour = face.verdict == job::FaceVerdict::Within  ? rgba(0.1f, 0.8f, 0.1f)
                                       : face.verdict == job::FaceVerdict::Above ? rgba(0.9f, 0.1f, 0.1f)
                                                                                 : rgba(0.6f, 0.6f, 0.6f, 0.5f);
    for (const uint32_t f : face.facets) {
      add_facet(m, part, f);
      m.colors.resize(m.points.size(), colour);
    }
    if (face.verdict != job::FaceVerdict::Above) continue;
    char text[160];
    std::snprintf(text, sizeof text, "face %u: up to %.2f mm (%s)", face.face, face.max_left_mm,
                  job::reason_name(face.main_reason()));
    visualization_msgs::Marker label =
        text_from_left(header_, "surface_notes", note++, face.most_at + 2.0 * face.normal, text, kLegendHeight,
                       kLegendChars);
    label.color = rgba(0.9f, 0.1f, 0.1f);
    toolpaths_.markers.push_back(label);
  }
  toolpaths_.markers.push_back(m);
  return toolpaths_;
}

visualization_msgs::MarkerArray JobMarkers::stock(const job::OperationView& view) const {
  const Mesh surface = stock::stock_surface(view.stock);
  std::vector<Vec3> centres(surface.faces.size());
  for (size_t f = 0; f < surface.faces.size(); ++f) {
    const auto& face = surface.faces[f];
    centres[f] = (surface.vertices[face[0]] + surface.vertices[face[1]] + surface.vertices[face[2]]) / 3.0;
  }
  const std::vector<float> left = stock::material_left_at(view.stock, view.part, view.setup.frame, centres);
  visualization_msgs::MarkerArray array;
  array.markers.push_back(delete_all_marker(header_));
  visualization_msgs::Marker m = base_marker(header_, "stock", 0, visualization_msgs::Marker::TRIANGLE_LIST);
  m.color = rgba(1, 1, 1);
  for (size_t f = 0; f < surface.faces.size(); ++f) {
    add_facet(m, surface, f);
    m.colors.resize(m.points.size(), material_left_colour(left[f], kTolerance, kFull));
  }
  array.markers.push_back(m);
  // The legend: beside the stock on its +x side (the right of the bundled rviz view, config/rosmill.rviz), one line
  // per colour from the stock's top down.
  const Box3& b = surface.faces.empty() ? view.part.bbox : surface.bbox;
  const Vec3 at(b.max.x() + kLegendGap, b.min.y(), b.max.z());
  char full[64], tol[64];
  std::snprintf(full, sizeof full, "red: %.1f mm or more left", kFull);
  std::snprintf(tol, sizeof tol, "green: within %.2f mm of the design", kTolerance);
  const std::vector<std::pair<std::string, std_msgs::ColorRGBA>> lines = {
      {"stock after " + view.report.name, rgba(1, 1, 1)},
      {tol, material_left_colour(0, kTolerance, kFull)},
      {"yellow: 1 mm left", material_left_colour(1.0f, kTolerance, kFull)},
      {full, material_left_colour(float(kFull), kTolerance, kFull)},
      {"magenta: below the design (gouge)", material_left_colour(-1.0f, kTolerance, kFull)}};
  for (size_t k = 0; k < lines.size(); ++k)
    array.markers.push_back(
        legend_line(header_, int(k), at - Vec3(0, 0, 2.0 * kLegendHeight * double(k)), lines[k].first, lines[k].second));
  return array;
}

}  // namespace rosmill::edge
