// What `rosmill register` and `rosmill inspect` share: the design and the scan read in their units, the
// registration's thresholds as options.
#pragma once
#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/scan/design_registration.hpp"
#include "rosmill/scan/report_json.hpp"

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

using scan::registration_json;

}  // namespace rosmill::core::cli
