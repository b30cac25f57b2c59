#include "rosmill/scan/thinning.hpp"

#include <algorithm>

#include "rosmill/cloud/cloud_prep.hpp"

namespace rosmill::core::scan {

std::vector<size_t> evenly_spaced(size_t count, size_t limit) {
  const size_t kept = std::min(count, limit);
  std::vector<size_t> out(kept);
  const double step = double(count) / double(kept);
  for (size_t i = 0; i < kept; ++i) out[i] = count <= limit ? i : size_t(double(i) * step);
  return out;
}

std::vector<Vec3> thin_evenly(const std::vector<Vec3>& points, size_t limit) {
  if (points.size() <= limit) return points;
  std::vector<Vec3> out;
  out.reserve(limit);
  for (const size_t i : evenly_spaced(points.size(), limit)) out.push_back(points[i]);
  return out;
}

std::vector<Vec3> thin_by_voxel(const std::vector<Vec3>& points, double leaf) {
  CloudPrepOptions prep;  // the one voxel filter of the project, nothing else of the preparation
  prep.origin_at_corner = false;
  prep.voxel = leaf;
  return prepare_cloud(points, prep).points;
}

}  // namespace rosmill::core::scan
