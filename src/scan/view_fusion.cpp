#include "rosmill/scan/view_fusion.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "rosmill/cloud/cloud_prep.hpp"
#include "rosmill/error.hpp"
#include "rosmill/number_text.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/scan/covered_share.hpp"
#include "rosmill/scan/plane_icp.hpp"
#include "rosmill/scan/principal_axes.hpp"
#include "rosmill/scan/surface_normals.hpp"
#include "rosmill/scan/thinning.hpp"

namespace rosmill::core::scan {
namespace {

constexpr int kNormalNeighbours = 12;  // of a reference point's normal

std::string view_name(const ScanView& v, size_t i) {
  return v.name.empty() ? "view " + std::to_string(i + 1) : "view " + std::to_string(i + 1) + " (" + v.name + ")";
}

// The thinned points of every view but `skip` (and only those before `end`), each through its current pose.
std::vector<Vec3> reference_points(const std::vector<std::vector<Vec3>>& thinned,
                                   const std::vector<Eigen::Matrix4d>& poses, size_t skip, size_t end,
                                   size_t limit) {
  std::vector<Vec3> all;
  for (size_t j = 0; j < end; ++j)
    if (j != skip) {
      const std::vector<Vec3> moved = transformed_points(poses[j], thinned[j]);
      all.insert(all.end(), moved.begin(), moved.end());
    }
  return thin_evenly(all, limit);
}

// Aligns view i onto the reference from `pose` and returns its new pose; `check` receives how well the overlap
// fixes it (pose_information.hpp) and how far it moved from its `given` pose. When the overlap fixes some
// direction only weakly, the alignment is run again from the given pose restricted to the well-fixed motions: the
// weak directions keep the given pose rather than take whatever the ICP drifted to along them.
Eigen::Matrix4d refine_view(const std::vector<Vec3>& view, const Eigen::Matrix4d& pose, const Eigen::Matrix4d& given,
                            const std::vector<Vec3>& reference, const FusionOptions& o, PhaseClock& clock,
                            ViewCorrection& check) {
  std::vector<double> variation;
  const std::vector<Vec3> normals = estimate_normals(reference, kNormalNeighbours, &variation);
  // A reference point whose neighbours straddle a step (an engraving's edge seen from above, its wall unseen)
  // has a tilted normal that is no face's: its pairs pull sideways by about the sampling spacing, like an
  // outline's, and are counted as outline pairs.
  // A relief's every point may vary that much (detail at the sampling's scale): a crease stands out from the
  // cloud's own median.
  std::vector<double> sorted = variation;
  std::nth_element(sorted.begin(), sorted.begin() + long(sorted.size() / 2), sorted.end());
  const double bound = std::max(o.crease_variation, o.crease_factor * sorted[sorted.size() / 2]);
  std::vector<char> creases(reference.size());
  for (size_t k = 0; k < reference.size(); ++k) creases[k] = variation[k] > bound;
  clock.lap("reference normals");
  const PlaneIcp icp(reference, normals, std::move(creases));
  clock.lap("ICP index");
  // The long reach only brings the view near: a third of its points do that, all of them make the fine fit.
  const auto align = [&](const Eigen::Matrix4d& from, const IcpMotions* allowed) {
    const Eigen::Matrix4d near = icp.align(thin_evenly(view, view.size() / 3), from, o.max_correction, 30, nullptr,
                                           allowed);
    return icp.align(view, near, o.max_correction / 5, 30, nullptr, allowed);
  };
  Eigen::Matrix4d t = align(pose, nullptr);
  clock.lap("ICP");
  const PrincipalFrame frame = principal_frame(reference);
  Box3 box;
  for (const Vec3& p : reference) box.add(p);
  const std::vector<Vec3> view_normals = estimate_normals(view);
  // A normal fitted to k neighbours whose scatter across it is the surface variation v (Pauly et al., "Efficient
  // simplification of point-sampled surfaces", 2002: v = l0 / (l0 + l1 + l2) about their centroid) tilts by
  // about sqrt(2 v / k): the noise across over the neighbourhood's extent, averaged over k points.
  // Their mean square over the reference: the tilted normals at its borders and creases count most.
  PoseInformationOptions information = o.information;
  if (information.normal_error == 0) {
    double sum = 0;
    for (double v : variation) sum += v;
    information.normal_error = std::sqrt(2 * sum / double(variation.size()) / double(kNormalNeighbours));
  }
  // The given pose within its stated error taken as 3 sigma.
  information.lock_sigma = o.lock_sigma;
  information.cloud_reference = true;
  information.given_mm = o.pose_error_mm / 3;
  information.given_deg = o.pose_error_deg / 3;
  check.information = pose_information(icp.pairs(view, view_normals, t, o.max_correction / 5,
                                                 o.information.outline_degrees),
                                       frame.centroid, frame.axes, 0.5 * box.size().norm(), icp.spacing(),
                                       information, "reference");
  clock.lap("pose information");
  const IcpMotions allowed{check.information.centre, check.information.fixed_motions(o.lock_sigma)};
  if (allowed.motions.cols() < 6) {
    check.locked = true;
    if (allowed.motions.cols() == 0) {
      t = given;
    } else {
      t = align(given, &allowed);
    }
    clock.lap("ICP");
  }
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : view) centroid += p;
  centroid = (given * (centroid / double(view.size())).homogeneous()).head<3>();
  const Eigen::Matrix4d correction = t * rigid_inverse(given);
  check.found = correction;
  check.moved_mm = ((correction * centroid.homogeneous()).head<3>() - centroid).norm();
  check.turned_deg = rotation_angle_deg(correction);
  return t;
}

// Marks the correction when the overlap does not fix it (its weak directions were locked at the given pose);
// withholds it (returns false) when it exceeds the stated pose error.
bool accept(ViewCorrection& c, const FusionOptions& o) {
  c.ambiguous = c.information.ambiguous();
  c.exceeds_pose_error = c.moved_mm > o.pose_error_mm || c.turned_deg > o.pose_error_deg;
  std::ostringstream why;
  if (c.exceeds_pose_error)
    why << "the correction (" << c.moved_mm << " mm at the view's centroid, " << c.turned_deg
        << " deg) exceeds the stated pose error (" << o.pose_error_mm << " mm, " << o.pose_error_deg << " deg)";
  if (c.ambiguous)
    why << (c.exceeds_pose_error ? "; " : "") << "the overlap fixes the view's pose only weakly along: "
        << c.information.describe()
        << (c.locked ? "; the view keeps its given pose along the motions fixed no better than a 1-sigma " : "")
        << (c.locked ? decimal_text(o.lock_sigma, 2) + " mm, corrected along the others"
                     : "; corrected along all of them");
  c.reason = why.str();
  c.applied = !c.exceeds_pose_error;
  return c.applied;
}

}  // namespace

void FusionOptions::check() const {
  if (rounds < 1 || rounds > 10) throw Error("fusion option rounds", "must lie in [1, 10]");
  if (!(max_correction > 0) || !std::isfinite(max_correction))
    throw Error("fusion option max_correction", "must be a positive number of mm");
  if (!(min_overlap >= 0 && min_overlap <= 1)) throw Error("fusion option min_overlap", "must lie in [0, 1]");
  if (icp_points < 100) throw Error("fusion option icp_points", "must be at least 100");
  if (!(pose_error_mm > 0) || !std::isfinite(pose_error_mm))
    throw Error("fusion option pose_error_mm", "must be a positive number of mm");
  if (!(pose_error_deg > 0) || !std::isfinite(pose_error_deg))
    throw Error("fusion option pose_error_deg", "must be a positive number of degrees");
  if (!(crease_variation > 0 && crease_variation <= 1.0 / 3))
    throw Error("fusion option crease_variation", "must lie in (0, 1/3]");
  if (!(crease_factor >= 1) || !std::isfinite(crease_factor))
    throw Error("fusion option crease_factor", "must be a number >= 1");
  if (!(lock_sigma > 0) || !std::isfinite(lock_sigma))
    throw Error("fusion option lock_sigma", "must be a positive number of mm");
  information.check();
}

PointCloud fuse_views(const std::vector<ScanView>& views, const FusionOptions& o, FusionReport* report) {
  const auto start = std::chrono::steady_clock::now();
  o.check();
  if (views.empty()) throw Error("fusion", "no view to fuse");
  FusionReport r;
  PhaseClock clock(r.phases);
  std::vector<Eigen::Matrix4d> poses;
  std::vector<std::vector<Vec3>> thinned;
  for (size_t i = 0; i < views.size(); ++i) {
    const std::string name = view_name(views[i], i);
    check_rigid(views[i].pose, name + " pose");
    if (views[i].cloud.points.size() < 20)
      throw Error(name, "has " + std::to_string(views[i].cloud.points.size()) + " points; at least 20 are needed");
    for (const Vec3& p : views[i].cloud.points)
      if (!p.allFinite()) throw Error(name, "holds a NaN or infinite point");
    poses.push_back(views[i].pose);
    thinned.push_back(thin_evenly(views[i].cloud.points, o.icp_points));
    r.points_in += views[i].cloud.points.size();
  }
  r.checks.assign(views.size(), ViewCorrection());
  if (o.refine && views.size() > 1) {
    for (int round = 0; round < o.rounds; ++round)
      for (size_t i = 1; i < views.size(); ++i) {
        const size_t end = round == 0 ? i : views.size();
        const std::vector<Vec3> reference = reference_points(thinned, poses, i, end, o.icp_points);
        clock.lap("checks, thinning, references");
        // The share only has to clear min_overlap: a few thousand points tell it.
        const double before =
            covered_share(transformed_points(poses[i], thin_evenly(thinned[i], 2000)), reference, o.max_correction);
        clock.lap("overlap");
        if (before < o.min_overlap)
          throw Error(view_name(views[i], i), "meets no other view within " + std::to_string(o.max_correction) +
                                                  " mm (" + std::to_string(100 * before) +
                                                  "% of its points): its pose is wrong or the views do not overlap");
        ViewCorrection& check = r.checks[i];
        const Eigen::Matrix4d refined = refine_view(thinned[i], poses[i], views[i].pose, reference, o, clock, check);
        poses[i] = accept(check, o) ? refined : views[i].pose;
      }
  }
  clock.lap("checks, thinning, references");
  for (const ViewCorrection& c : r.checks) {
    r.withheld += !c.applied;
    r.ambiguous += c.ambiguous;
  }
  std::vector<Vec3> fused;
  fused.reserve(r.points_in);
  for (size_t i = 0; i < views.size(); ++i) {
    r.corrections.push_back(poses[i] * rigid_inverse(views[i].pose));
    const std::vector<Vec3> moved = transformed_points(poses[i], views[i].cloud.points);
    fused.insert(fused.end(), moved.begin(), moved.end());
    clock.lap("merge");
    if (views.size() > 1)
      r.overlaps.push_back(covered_share(transformed_points(poses[i], thinned[i]),
                                         reference_points(thinned, poses, i, views.size(), o.icp_points),
                                         o.max_correction / 5));
    clock.lap("overlap");
  }
  CloudPrepOptions prep;  // the project's voxel and outlier filters, no reorientation
  prep.origin_at_corner = false;
  prep.voxel = o.voxel;
  prep.outlier_neighbours = o.outlier_neighbours;
  prep.outlier_stddev = o.outlier_stddev;
  PointCloud out = prepare_cloud(fused, prep);
  clock.lap("voxel grid, outliers");
  r.points_out = out.points.size();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report) *report = std::move(r);
  return out;
}

}  // namespace rosmill::core::scan
