// Multi-view fusion: several scans, each with the sensor's pose, brought into one frame and fused.
//
//   1. Each view's points go through its pose (view frame -> common frame, mm).
//   2. Refinement, because poses from a robot or a calibration are off by a little: the first view is the
//      reference; each further view is aligned by point-to-plane ICP onto the views before it, then, for
//      `rounds` - 1 more rounds, each onto all the others (one view against the rest, as Pulli, "Multiview
//      registration for large data sets" (1999), does it). A view that meets no other within
//      `max_correction` is refused: its pose is wrong or the views do not overlap.
//      Each refinement is checked (pose_information.hpp, in the principal frame of the points it was aligned
//      onto): when the correction moves the view further than the stated pose error allows (at the view's
//      centroid, or turns it by more), it is withheld and the view keeps its given pose; when the overlap fixes a
//      direction of the view's pose only weakly (views of a plate from above, of a cylinder from its side), the
//      report marks it ambiguous, naming the weak directions; a motion fixed no better than `lock_sigma` is
//      locked: the view is aligned again from its given pose along the well-fixed motions only and keeps its
//      given pose along the others. A correction is never applied silently.
//   3. The union is thinned by a voxel grid and cleared of outliers (PCL, the cloud preparation's filters).
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/scan/phase_clock.hpp"
#include "rosmill/scan/pose_information.hpp"

namespace rosmill::core::scan {

struct ScanView {
  PointCloud cloud;                                    // mm, in the view's (sensor's) frame
  Eigen::Matrix4d pose = Eigen::Matrix4d::Identity();  // view frame -> common frame, mm
  std::string name;                                    // for errors ("view 2", a file name)
};

struct FusionOptions {
  bool refine = true;
  int rounds = 2;                // 1: each view onto those before it only
  double max_correction = 5.0;   // mm: ICP pairs points at most this far apart
  double min_overlap = 0.05;     // share of a view's points that must lie near the others after refinement
  size_t icp_points = 15000;     // per view and per reference, evenly thinned
  double voxel = 0.0;            // mm: voxel grid leaf of the fused cloud; 0 = off
  int outlier_neighbours = 0;    // statistical outlier removal over K neighbours; 0 = off
  double outlier_stddev = 2.0;
  double pose_error_mm = 10.0;   // how far a given pose may be off: a larger correction (at the view's centroid) ...
  double pose_error_deg = 2.0;   // ... or a larger turn is withheld
  PoseInformationOptions information;  // when a direction of a view's pose counts as weak
  double lock_sigma = 0.25;      // mm: a motion the overlap fixes no better (1 sigma) keeps the given pose
  // A reference point whose surface variation exceeds both this and `crease_factor` times the reference's median
  // has no face's normal (its neighbours straddle a step): its pairs count as outline pairs.
  double crease_variation = 0.02;
  double crease_factor = 10;
  void check() const;
};

// What became of one view's correction.
struct ViewCorrection {
  bool applied = true;           // false: withheld (beyond the pose error), the view kept its given pose
  bool ambiguous = false;        // the overlap fixes some direction only weakly (information.weak names them)
  bool exceeds_pose_error = false;
  bool locked = false;           // some motions kept the given pose (sigma above lock_sigma); the others were corrected
  Eigen::Matrix4d found = Eigen::Matrix4d::Identity();  // the correction found (common frame), applied or not
  double moved_mm = 0, turned_deg = 0;  // ... its move at the view's centroid and its turn
  std::string reason;            // why withheld; empty when applied
  PoseInformation information;   // of the view's last refinement, in the reference's principal frame
};

struct FusionReport {
  size_t points_in = 0, points_out = 0;
  std::vector<Eigen::Matrix4d> corrections;  // per view: applied on top of its pose (identity for the first)
  std::vector<double> overlaps;              // per view: share of its points near the others, after refinement
  std::vector<ViewCorrection> checks;        // per view (the first: the reference, applied with nothing to check)
  size_t withheld = 0;                       // corrections withheld
  size_t ambiguous = 0;                      // views marked ambiguous
  double seconds = 0;
  PhaseSeconds phases;                       // the same time by phase (thinning, overlap, normals, ICP, ...)
};

// Throws Error naming the view on bad input (no views, an empty view, a pose with NaN or not rigid, a view that
// meets no other) and on bad options.
PointCloud fuse_views(const std::vector<ScanView>& views, const FusionOptions& options = {},
                      FusionReport* report = nullptr);

}  // namespace rosmill::core::scan
