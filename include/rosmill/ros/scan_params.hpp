// The scan_registrar's parameters for fusion and registration (~voxel, ~outlier_neighbours, ~fusion_rounds,
// ~max_correction, ~inlier_distance, ~min_inlier_share, ~max_rms, ~min_overlap), each checked against its range.
#pragma once
#include <ros/node_handle.h>

#include "rosmill/ros/namespaces.hpp"
#include "rosmill/scan/design_registration.hpp"
#include "rosmill/scan/view_fusion.hpp"

namespace rosmill::edge {

void read_scan_options(const ::ros::NodeHandle& pnh, scan::FusionOptions& fusion, scan::RegistrationOptions& registration);

}  // namespace rosmill::edge
