// Design-to-scan registration: the rigid transform that puts the design (an STL, millimetres) where the scanned
// part is, with no initial guess.
//
//   1. Global: principal-axes candidates (principal_axes.hpp), each pulled in by coarse point-to-plane ICP on a
//      voxel-thinned scan against an area-weighted sampling of the design, side by side in rounds where a clearly
//      worse candidate drops out; the best fit wins.
//   2. Fine: point-to-plane ICP (plane_icp.hpp) with shrinking pairing distance on up to `fine_points` scan points.
//   3. Fitness from exact point-to-triangle distances (mesh_distance.hpp): RMS of the inliers, inlier share,
//      overlap (share of the design the scan covers); how well the fine step's pairs fix each of the six degrees
//      of freedom in the design's principal frame, with a sigma per direction that covers the outlines' bias
//      (pose_information.hpp); ambiguity when another candidate pose fits as well, or when a direction is fixed
//      only weakly (a turned part about its axis, a plate seen from above along its faces).
//   4. Refusal (Error, nothing returned) below the thresholds of the options.
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/scan/phase_clock.hpp"
#include "rosmill/scan/pose_information.hpp"

namespace rosmill::core::scan {

struct RegistrationOptions {
  double inlier_distance = 0.5;     // mm: a scan point this close to the design is an inlier
  double min_inlier_share = 0.6;    // refuse below (the scan shows something else, or the wrong part)
  double max_rms = 0.25;            // mm: refuse above
  double min_overlap = 0.05;        // refuse when the scan covers less of the design's surface
  double moment_tolerance = 0.1;    // relative gap under which two principal moments count as equal
  double ambiguity_rms = 1.25;      // another pose within this factor of the best RMS ...
  double ambiguity_share = 0.02;    // ... and this much inlier share is an equally good fit
  size_t design_points = 60000;     // area-weighted design sampling (the ICP target)
  size_t coarse_points = 3000;      // about this many voxel-thinned scan points for the global step
  size_t fine_points = 20000;       // at most this many scan points for the fine step and the fitness
  uint64_t seed = 1;                // of the design sampling
  PoseInformationOptions information;  // when a direction counts as weak, the sigmas' floor
  void check() const;               // Error naming the option out of range
};

struct RegistrationResult {
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();  // design -> scan, mm
  double rms = 0;            // mm, over the inliers
  double inlier_share = 0;   // of the scan points used
  double overlap = 0;        // share of the design's surface with a scan point nearby
  bool ambiguous = false;
  std::string ambiguity;     // why, when ambiguous
  std::vector<Eigen::Matrix4d> alternatives;  // other poses that fit about as well
  double translation_sigma = 0;  // mm, 1-sigma along the worst direction (infinity: a free one)
  double rotation_sigma_deg = 0;
  PoseInformation information;   // per degree of freedom, in the design's principal frame
  size_t candidates = 0;     // global candidates tried
  size_t scan_points_used = 0;
  double global_seconds = 0, fine_seconds = 0;
  PhaseSeconds phases;       // the same time by phase (design sampling, indexes, ICP, exact distances, ...)
};

// Throws Error on bad input (no design surface, an empty scan, bad options) and when the fit is refused.
RegistrationResult register_design(const Mesh& design, const PointCloud& scan, const RegistrationOptions& options = {});

// The result as text, one fact a line.
std::string format_registration(const RegistrationResult& r);

}  // namespace rosmill::core::scan
