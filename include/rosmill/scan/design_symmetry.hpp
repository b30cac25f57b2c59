// The symmetries of a design: the rigid motions, other than the identity, that map its surface onto itself (a plate
// with a mirror-symmetric hole pattern turned over, a cube turned a quarter, a square flange turned about its
// axis). A scan cannot tell the poses a symmetry relates apart however much of the part it shows, so registration
// reports them as alternatives; they put the same surface in the same place.
//
// A symmetry keeps the surface's centroid and maps its principal frame onto itself, so the search runs over the
// motions that keep the principal frame (principal_axes.hpp): the three half turns when the moments differ, every
// turn about the free axis and every turn-over when two are near-equal, the rotations of the cube when all three
// are. Each motion is first scored on a grid of the cells near the surface (cheap: a lookup a point), at an angular
// step fine enough that the nearest step to a true symmetry moves no point by more than half a cell; the few that
// score as symmetries are refined by point-to-plane ICP of the design onto itself and kept when the exact distances
// confirm them.
#pragma once
#include <vector>

#include <Eigen/Core>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/scan/mesh_distance.hpp"
#include "rosmill/scan/plane_icp.hpp"
#include "rosmill/scan/principal_axes.hpp"
#include "rosmill/scan/surface_sample.hpp"

namespace rosmill::core::scan {

struct SymmetryOptions {
  double moment_tolerance = 0.1;  // as in registration: moments this close count as equal
  double tolerance = 0.05;        // mm: the RMS distance of the design moved onto itself
  double min_share = 0.98;        // of the design's points within `inlier_distance` of itself once moved
  double inlier_distance = 0.5;   // mm
};

// Whether `motion` maps the design (`points` on its surface) onto itself: the share within the inlier distance and
// their RMS distance within the options' bounds.
bool maps_onto_itself(const MeshDistance& distance, const std::vector<Vec3>& points, const Eigen::Matrix4d& motion,
                      const SymmetryOptions& options);

// The design's symmetries (design -> design), each a distinct motion; at most `limit`. `sample` is an area-weighted
// sampling of the design with its normals, `icp` its point-to-plane ICP target and `distance` its exact distance.
std::vector<Eigen::Matrix4d> design_symmetries(const Mesh& design, const SurfaceSample& sample,
                                               const PrincipalFrame& frame, const PlaneIcp& icp,
                                               const MeshDistance& distance, const SymmetryOptions& options,
                                               size_t limit = 8);

}  // namespace rosmill::core::scan
