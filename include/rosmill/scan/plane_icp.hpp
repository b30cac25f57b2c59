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
#include "rosmill/scan/pose_information.hpp"

namespace rosmill::core::scan {

// How an alignment ended.
struct IcpOutcome {
  int steps = 0;           // steps taken
  bool converged = false;  // the last step moved less than 1e-6 mm and 1e-6 rad
  size_t pairs = 0;        // point pairs of the last step (fewer than 6: it stopped there)
};

// The motions an alignment may make: columns (turn in radians, slide in mm), the turns about `centre`, in the
// fixed frame. Each step solves the point-to-plane equations only within their span, so the pose keeps its start
// value along every motion outside it (a direction the pairs fix too weakly to be trusted is locked).
struct IcpMotions {
  Vec3 centre = Vec3::Zero();
  Eigen::Matrix<double, 6, Eigen::Dynamic> motions;
};

class PlaneIcp {
 public:
  // The fixed surface (its k-d tree is built once, for every align()). `creases` (empty, or one flag a point)
  // marks points whose normal is no face's (estimated across a step or an edge): pairs() counts a pair with one
  // as an outline pair. Throws Error when empty or the sizes differ.
  PlaneIcp(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, std::vector<char> creases = {});
  ~PlaneIcp();
  PlaneIcp(const PlaneIcp&) = delete;
  PlaneIcp& operator=(const PlaneIcp&) = delete;

  // The transform (moving -> fixed) refined from `start`, pairing points at most `max_distance` mm apart, for at
  // most `iterations` steps (fewer once a step moves less than 1e-6 mm and 1e-6 rad); only along `allowed` when
  // given.
  Eigen::Matrix4d align(const std::vector<Vec3>& moving, const Eigen::Matrix4d& start, double max_distance,
                        int iterations, IcpOutcome* outcome = nullptr, const IcpMotions* allowed = nullptr) const;

  // The pairs a step at `pose` (moving -> fixed) uses: each moving point with its nearest fixed point within
  // `max_distance` mm, in the fixed frame, with the fixed normal and the residual. A pair is an outline pair when
  // the moving point's own normal (`moving_normals`, before the pose; signs arbitrary) differs from its pair's by
  // more than `outline_degrees` and no moving point within `max_distance` of the pair's face has a normal that
  // agrees with it (that face is not seen: a plate's side wall from above; at an edge whose two faces are both
  // seen, the pair is a surface pair), or when its fixed point is a crease. Throws Error when the sizes differ.
  std::vector<PlanePair> pairs(const std::vector<Vec3>& moving, const std::vector<Vec3>& moving_normals,
                               const Eigen::Matrix4d& pose, double max_distance, double outline_degrees) const;

  // The fixed surface's sampling spacing, mm: twice the median distance from a point to its nearest neighbour
  // (for points spread at random over an area A, about sqrt(A / count); for a grid, twice its pitch).
  double spacing() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rosmill::core::scan
