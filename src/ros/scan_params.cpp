#include "rosmill/ros/scan_params.hpp"

#include "rosmill/ros/params.hpp"

namespace rosmill::edge {

void read_scan_options(const ::ros::NodeHandle& pnh, scan::FusionOptions& fusion, scan::RegistrationOptions& r) {
  fusion.refine = bool_param(pnh, "refine_views", true);
  fusion.voxel = double_param(pnh, "voxel", 0.0, 0.0, 100.0);
  fusion.outlier_neighbours = int_param(pnh, "outlier_neighbours", 0, 0, 200);
  fusion.rounds = int_param(pnh, "fusion_rounds", fusion.rounds, 1, 10);
  fusion.max_correction = double_param(pnh, "max_correction", fusion.max_correction, 0.01, 1000.0);
  r.inlier_distance = double_param(pnh, "inlier_distance", r.inlier_distance, 1e-3, 100.0);
  r.min_inlier_share = double_param(pnh, "min_inlier_share", r.min_inlier_share, 0.0, 1.0);
  r.max_rms = double_param(pnh, "max_rms", r.max_rms, 1e-4, 100.0);
  r.min_overlap = double_param(pnh, "min_overlap", r.min_overlap, 0.0, 1.0);
}

}  // namespace rosmill::edge
