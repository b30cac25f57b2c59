// The scan_registrar's replies and view: a registration and an inspection as service responses (metres, radians),
// and the scan coloured by its signed distance to the design as markers (the verifier's colour bands: reds below
// the design, blues above), with the largest excess marked and labelled.
#pragma once
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include "rosmill/InspectScan.h"
#include "rosmill/RegisterScan.h"
#include "rosmill/ros/namespaces.hpp"
#include "rosmill/scan/design_registration.hpp"
#include "rosmill/scan/inspection.hpp"
#include "rosmill/scan/view_fusion.hpp"

namespace rosmill::edge {

// The pose `r.transform` (design -> scan, mm) as `parent` -> `child`.
geometry_msgs::TransformStamped workpiece_transform(const scan::RegistrationResult& r, const std::string& parent,
                                                    const std::string& child);

void fill_response(const scan::RegistrationResult& r, const std::string& parent, const std::string& child,
                   RegisterScan::Response& res);
void fill_response(const scan::InspectionReport& r, double tolerance_mm, bool registered, InspectScan::Response& res);

// The services' one-line answers. A fusion names each view whose correction was held back or is ambiguous: a
// correction the overlap does not fix is never applied silently.
std::string fusion_summary(const scan::FusionReport& r, size_t views, const std::string& frame);
std::string registration_summary(const scan::RegistrationResult& r, bool dry_run);
std::string inspection_summary(const scan::InspectionReport& r);

// At most `max_points` of the scan (evenly thinned), in `header.frame_id` (the workpiece frame).
visualization_msgs::MarkerArray deviation_markers(const scan::InspectionReport& r, double tolerance_mm,
                                                  const std_msgs::Header& header, size_t max_points = 100000);

}  // namespace rosmill::edge
