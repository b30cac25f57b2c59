#include "rosmill/scan/thinning.hpp"

#include "rosmill/cloud/cloud_prep.hpp"

namespace rosmill::core::scan {

std::vector<Vec3> thin_evenly(const std::vector<Vec3>& points, size_t limit) {
  if (points.size() <= limit) return points;
  std::vector<Vec3> out;
  out.reserve(limit);
  const double step = double(points.size()) / double(limit);
  for (size_t i = 0; i < limit; ++i) out.push_back(points[size_t(double(i) * step)]);
  return out;
}

std::vector<Vec3> thin_by_voxel(const std::vector<Vec3>& points, double leaf) {
  CloudPrepOptions prep;  // the one voxel filter of the project, nothing else of the preparation
  prep.origin_at_corner = false;
  prep.voxel = leaf;
  return prepare_cloud(points, prep).points;
}

}  // namespace rosmill::core::scan
