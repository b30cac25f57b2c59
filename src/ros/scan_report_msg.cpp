#include "rosmill/ros/scan_report_msg.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/markers.hpp"
#include "rosmill/scan/report_json.hpp"
#include "rosmill/verify/deviation_map.hpp"

namespace rosmill::edge {
namespace {

constexpr double kRadianPerDegree = M_PI / 180.0;

std_msgs::ColorRGBA colour_of(const verify::Rgb& c) { return rgba(c.r / 255.0f, c.g / 255.0f, c.b / 255.0f); }

}  // namespace

geometry_msgs::TransformStamped workpiece_transform(const scan::RegistrationResult& r, const std::string& parent,
                                                    const std::string& child) {
  const Eigen::Matrix3d rotation = r.transform.topLeftCorner<3, 3>();
  return to_transform_msg(parent, child, Eigen::Quaterniond(rotation).normalized(),
                          r.transform.topRightCorner<3, 1>() * kMetrePerMm);
}

void fill_response(const scan::RegistrationResult& r, const std::string& parent, const std::string& child,
                   RegisterScan::Response& res) {
  res.transform = workpiece_transform(r, parent, child);
  res.rms = to_metres(r.rms);
  res.inlier_share = r.inlier_share;
  res.overlap = r.overlap;
  res.ambiguous = r.ambiguous;
  res.ambiguity = r.ambiguity;
  res.translation_sigma = std::isfinite(r.translation_sigma) ? to_metres(r.translation_sigma) : -1.0;
  res.rotation_sigma = std::isfinite(r.rotation_sigma_deg) ? r.rotation_sigma_deg * kRadianPerDegree : -1.0;
  res.report_json = scan::registration_json(r).dump();
}

void fill_response(const scan::InspectionReport& r, double tolerance_mm, bool registered, InspectScan::Response& res) {
  res.points = static_cast<uint32_t>(r.deviations.size());
  res.mean = to_metres(r.mean);
  res.rms = to_metres(r.rms);
  res.largest_excess = to_metres(r.largest_excess.distance);
  res.largest_excess_at = to_point_msg(r.largest_excess.place);
  res.largest_deficit = to_metres(r.largest_deficit.distance);
  res.largest_deficit_at = to_point_msg(r.largest_deficit.place);
  res.within_tolerance = static_cast<uint32_t>(r.within_tolerance);
  res.above_tolerance = static_cast<uint32_t>(r.above_tolerance);
  res.below_tolerance = static_cast<uint32_t>(r.below_tolerance);
  res.report_json = scan::inspection_json(r, tolerance_mm, registered).dump();
}

visualization_msgs::MarkerArray deviation_markers(const scan::InspectionReport& r, double tolerance_mm,
                                                  const std_msgs::Header& header, size_t max_points) {
  visualization_msgs::MarkerArray array;
  array.markers.push_back(delete_all_marker(header));
  visualization_msgs::Marker points = base_marker(header, "scan_deviation", 0, visualization_msgs::Marker::POINTS);
  points.scale.x = points.scale.y = 0.0008;  // 0.8 mm squares
  const std::vector<verify::DeviationBand> bands = verify::deviation_bands(tolerance_mm);
  const size_t stride = std::max<size_t>(1, (r.points.size() + max_points - 1) / std::max<size_t>(max_points, 1));
  points.points.reserve(r.points.size() / stride + 1);
  points.colors.reserve(r.points.size() / stride + 1);
  for (size_t i = 0; i < r.points.size(); i += stride) {
    points.points.push_back(to_point_msg(r.points[i]));
    points.colors.push_back(colour_of(bands[verify::deviation_band(r.deviations[i], true, tolerance_mm)].colour));
  }
  array.markers.push_back(points);
  if (r.largest_excess.distance > tolerance_mm) {
    visualization_msgs::Marker at = base_marker(header, "largest_excess", 0, visualization_msgs::Marker::SPHERE);
    at.pose.position = to_point_msg(r.largest_excess.place);
    at.scale.x = at.scale.y = at.scale.z = 0.004;
    at.color = rgba(0.2f, 0.4f, 1.0f);
    array.markers.push_back(at);
    visualization_msgs::Marker label =
        base_marker(header, "largest_excess", 1, visualization_msgs::Marker::TEXT_VIEW_FACING);
    label.pose.position = to_point_msg(r.largest_excess.place + Vec3(0, 0, 8));
    label.scale.z = 0.005;
    label.color = rgba(1.0f, 1.0f, 1.0f);
    char text[96];
    std::snprintf(text, sizeof text, "+%.3f mm above the design", r.largest_excess.distance);
    label.text = text;
    array.markers.push_back(label);
  }
  return array;
}

std::string fusion_summary(const scan::FusionReport& r, size_t views, const std::string& frame) {
  std::string withheld;
  for (size_t i = 0; i < r.checks.size(); ++i)
    if (!r.checks[i].applied || r.checks[i].ambiguous)
      withheld += "; view " + std::to_string(i + 1) +
                  (r.checks[i].applied ? " is ambiguous: " : " keeps its given pose: ") + r.checks[i].reason;
  return std::to_string(views) + " views fused: " + std::to_string(r.points_out) + " of " +
         std::to_string(r.points_in) + " points in '" + frame + "'" + withheld;
}

std::string registration_summary(const scan::RegistrationResult& r, bool dry_run) {
  return std::string(dry_run ? "fit (dry run, not published)" : "published") + ": rms " + std::to_string(r.rms) +
         " mm, inlier share " + std::to_string(r.inlier_share) + (r.ambiguous ? ", ambiguous: " + r.ambiguity : "");
}

std::string inspection_summary(const scan::InspectionReport& r) {
  return std::to_string(r.deviations.size()) + " points, largest excess " + std::to_string(r.largest_excess.distance) +
         " mm, " + std::to_string(r.above_tolerance) + " above the tolerance";
}

}  // namespace rosmill::edge
