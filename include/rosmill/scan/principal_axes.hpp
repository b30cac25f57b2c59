// The global step of registration without an initial guess: principal axes. The second moments of the design's
// surface and of the scan give each a frame (centroid, axes by decreasing moment); the poses that map one frame
// onto the other are the candidates. An axis is defined only up to its sign, so there are four proper rotations;
// when two moments are near-equal the axes in their plane are arbitrary (a turned part), and when all three are
// (a cube, a sphere) every axis is: the candidates then sweep those freedoms, and several will fit.
// (Principal axes alignment as the coarse step of ICP: e.g. Rusinkiewicz & Levoy, "Efficient variants of the
// ICP algorithm", 2001, on initial alignment.)
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::scan {

struct PrincipalFrame {
  Vec3 centroid = Vec3::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns, decreasing moment; a right-handed frame
  Vec3 moments = Vec3::Zero();                         // decreasing
};

// Throws Error when fewer than 4 points are given.
PrincipalFrame principal_frame(const std::vector<Vec3>& points);

// How many of the three moments are near-equal to another (0, 2 or 3) at a relative gap below `tolerance`.
int near_equal_moments(const Vec3& moments, double tolerance);

// Candidate poses design -> scan: 4 without near-equal moments; rotations about the free axis every `step_deg`
// (and turned over) with two; the 24 rotations of the cube with three.
std::vector<Eigen::Matrix4d> principal_axes_candidates(const PrincipalFrame& design, const PrincipalFrame& scan,
                                                       double tolerance, double step_deg = 30);

// `pose` (design -> scan) composed with each motion of the design that keeps its principal frame, other than the
// identity (about a free axis every `step_deg`): where a second minimum lies when the design is (nearly) symmetric
// on the side a scan shows.
std::vector<Eigen::Matrix4d> principal_symmetry_probes(const Eigen::Matrix4d& pose, const PrincipalFrame& design,
                                                       double tolerance, double step_deg);

}  // namespace rosmill::core::scan
