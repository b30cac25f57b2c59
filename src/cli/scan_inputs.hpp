// What `rosmill register` and `rosmill inspect` share: the design and the scan read in their units, the
// registration's thresholds as options, the result as JSON.
#pragma once
#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/scan/design_registration.hpp"

namespace rosmill::core::cli {

struct ScanInputs {
  std::string design, scan, units = "mm", scan_units = "m";
  scan::RegistrationOptions registration;
  bool json = false;

  Mesh read_design() const {
    StlReadOptions o;
    o.units = parse_units(units, "--units");
    return read_stl(design, o);
  }
  PointCloud read_scan() const {
    CloudReadOptions o;
    o.units = parse_units(scan_units, "--scan-units");
    return read_cloud(scan, o);
  }
};

inline void add_scan_inputs(CLI::App* cmd, ScanInputs& a) {
  cmd->add_option("DESIGN", a.design, "the design: STL (also .stl.gz)")->required();
  cmd->add_option("SCAN", a.scan, "the scan: PCD or PLY")->required();
  cmd->add_option("--units", a.units, "units of the design's numbers: mm, inch or m (default mm)")
      ->check(CLI::IsMember({"mm", "inch", "in", "m"}));
  cmd->add_option("--scan-units", a.scan_units, "units of the scan's numbers (default m, the ROS custom)")
      ->check(CLI::IsMember({"mm", "inch", "in", "m"}));
  auto& r = a.registration;
  cmd->add_option("--inlier-distance", r.inlier_distance, "mm: a scan point this close to the design is an inlier (0.5)");
  cmd->add_option("--min-inlier-share", r.min_inlier_share, "refuse below this share of inliers (0.6)");
  cmd->add_option("--max-rms", r.max_rms, "mm: refuse above this RMS distance of the inliers (0.25)");
  cmd->add_option("--min-overlap", r.min_overlap, "refuse when the scan covers less of the design (0.05)");
  cmd->add_flag("--json", a.json, "print one JSON object");
}

inline nlohmann::ordered_json matrix_json(const Eigen::Matrix4d& t) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (int i = 0; i < 4; ++i) rows.push_back({t(i, 0), t(i, 1), t(i, 2), t(i, 3)});
  return rows;
}

inline nlohmann::ordered_json registration_json(const scan::RegistrationResult& r) {
  nlohmann::ordered_json j;
  j["transform"] = matrix_json(r.transform);
  j["rms"] = r.rms;
  j["inlier_share"] = r.inlier_share;
  j["overlap"] = r.overlap;
  j["ambiguous"] = r.ambiguous;
  j["ambiguity"] = r.ambiguity;
  j["alternatives"] = nlohmann::ordered_json::array();
  for (const auto& a : r.alternatives) j["alternatives"].push_back(matrix_json(a));
  j["translation_sigma_mm"] = std::isfinite(r.translation_sigma) ? nlohmann::ordered_json(r.translation_sigma) : nullptr;
  j["rotation_sigma_deg"] = std::isfinite(r.rotation_sigma_deg) ? nlohmann::ordered_json(r.rotation_sigma_deg) : nullptr;
  j["candidates"] = r.candidates;
  j["scan_points_used"] = r.scan_points_used;
  j["seconds"] = r.global_seconds + r.fine_seconds;
  return j;
}

}  // namespace rosmill::core::cli
