#include "rosmill/scan/view_fusion.hpp"

#include <chrono>
#include <cmath>

#include "rosmill/cloud/cloud_prep.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/scan/covered_share.hpp"
#include "rosmill/scan/plane_icp.hpp"
#include "rosmill/scan/surface_normals.hpp"
#include "rosmill/scan/thinning.hpp"

namespace rosmill::core::scan {
namespace {

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

// Aligns view i onto the reference and returns its new pose.
Eigen::Matrix4d refine_view(const std::vector<Vec3>& view, const Eigen::Matrix4d& pose,
                            const std::vector<Vec3>& reference, double max_correction, PhaseClock& clock) {
  const std::vector<Vec3> normals = estimate_normals(reference);
  clock.lap("reference normals");
  const PlaneIcp icp(reference, normals);
  clock.lap("ICP index");
  // The long reach only brings the view near: a third of its points do that, all of them make the fine fit.
  Eigen::Matrix4d t = icp.align(thin_evenly(view, view.size() / 3), pose, max_correction, 30);
  t = icp.align(view, t, max_correction / 5, 30);
  clock.lap("ICP");
  return t;
}

}  // namespace

void FusionOptions::check() const {
  if (rounds < 1 || rounds > 10) throw Error("fusion option rounds", "must lie in [1, 10]");
  if (!(max_correction > 0) || !std::isfinite(max_correction))
    throw Error("fusion option max_correction", "must be a positive number of mm");
  if (!(min_overlap >= 0 && min_overlap <= 1)) throw Error("fusion option min_overlap", "must lie in [0, 1]");
  if (icp_points < 100) throw Error("fusion option icp_points", "must be at least 100");
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
        poses[i] = refine_view(thinned[i], poses[i], reference, o.max_correction, clock);
      }
  }
  clock.lap("checks, thinning, references");
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
