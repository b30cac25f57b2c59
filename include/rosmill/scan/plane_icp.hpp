// Point-to-plane ICP, linear least squares per step: moving points are pulled onto a fixed surface given as points
// with normals. Chen & Medioni, "Object modelling by registration of multiple range images" (1992): minimising the
// distance to the tangent plane converges in far fewer steps than point-to-point ICP (Besl & McKay 1992) and
// slides along the surface to its exact fit. In double precision, the pairs found and summed on every core
// (the k-d tree of point_index.hpp, built once per fixed surface).
#pragma once
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::scan {

// How an alignment ended.
struct IcpOutcome {
  int steps = 0;           // steps taken
  bool converged = false;  // the last step moved less than 1e-6 mm and 1e-6 rad
  size_t pairs = 0;        // point pairs of the last step (fewer than 6: it stopped there)
};

class PlaneIcp {
 public:
  // The fixed surface (its k-d tree is built once, for every align()). Throws Error when empty or the sizes differ.
  PlaneIcp(const std::vector<Vec3>& points, const std::vector<Vec3>& normals);
  ~PlaneIcp();
  PlaneIcp(const PlaneIcp&) = delete;
  PlaneIcp& operator=(const PlaneIcp&) = delete;

  // The transform (moving -> fixed) refined from `start`, pairing points at most `max_distance` mm apart, for at
  // most `iterations` steps (fewer once a step moves less than 1e-6 mm and 1e-6 rad).
  Eigen::Matrix4d align(const std::vector<Vec3>& moving, const Eigen::Matrix4d& start, double max_distance,
                        int iterations, IcpOutcome* outcome = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rosmill::core::scan
