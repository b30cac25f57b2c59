// The cells of a regular grid that lie near a surface given by points on it: a test "is this point near the
// surface" at the cost of one lookup, where an exact point-to-triangle distance costs a tree descent. For scoring
// many poses of many points (design symmetries, the rounds of the registration's race), where an approximate share
// of points near the surface is all that is asked.
#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::scan {

class NearSurfaceCells {
 public:
  // Marks each point's cell and its 26 neighbours over `box` (the points' box or larger): a point within `cell`
  // of a surface point always finds its cell marked, one farther than 2 sqrt(3) cells (3.5) never does. `points`
  // must be no sparser than a cell. Memory: one byte a cell over the box grown by two cells.
  NearSurfaceCells(const std::vector<Vec3>& points, const Box3& box, double cell);

  bool near(const Vec3& p) const;
  // The share of `points`, moved by `motion`, that are near the surface.
  double share_near(const std::vector<Vec3>& points, const Eigen::Matrix4d& motion) const;

 private:
  Eigen::Vector3i cell_of(const Vec3& p) const;
  size_t index(const Eigen::Vector3i& c) const { return (size_t(c.z()) * size_[1] + c.y()) * size_[0] + c.x(); }

  double cell_;
  Vec3 origin_;
  int size_[3];
  std::vector<uint8_t> marked_;
};

}  // namespace rosmill::core::scan
