// A scan as planning input: the one preparation step (cloud_prep.hpp: orientation, origin, voxel and outlier
// filters) and the hole policy, with the options the command line (--orient, --origin, --voxel, --outliers,
// --holes) and the ROS planner (parameters of the same names) both take.
#pragma once
#include <string>
#include <vector>

#include "rosmill/cloud/cloud_holes.hpp"
#include "rosmill/cloud/cloud_prep.hpp"

namespace rosmill::core {

struct CloudInputOptions {
  std::string orient = "none";    // none | ransac (fit the base plane) | lowest (fit the lowest points)
  std::string origin = "corner";  // corner (program origin at the stock corner) | keep
  double voxel = 0.0;             // mm: voxel downsampling leaf; 0 = off
  int outliers = 0;               // statistical outlier removal over K neighbours; 0 = off
  std::string holes = "bridge";   // bridge (lids at the highest neighbour) | skip (no cut over a hole)
};

// The preparation options; errors name the option as `prefix` + its name ("--orient", "~orient").
CloudPrepOptions cloud_prep_options(const CloudInputOptions& options, const std::string& prefix);
HolePolicy cloud_hole_policy(const CloudInputOptions& options, const std::string& prefix);

// The cloud (millimetres, already in the frame the options start from) prepared for planning.
PointCloud prepare_input_cloud(const std::vector<Vec3>& points, const CloudInputOptions& options,
                               const std::string& prefix, CloudPrepReport* report = nullptr);

}  // namespace rosmill::core
