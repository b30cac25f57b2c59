#include "rosmill/cloud/cloud_prep.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>

#include "rosmill/cloud/cloud_grid.hpp"
#include "rosmill/cloud/voxel_grid.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/rigid_transform.hpp"

namespace rosmill::core {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

// PCL works in float: points go in relative to `origin` so millimetre clouds keep their precision.
Cloud::Ptr to_pcl(const std::vector<Vec3>& pts, const Vec3& origin) {
  Cloud::Ptr c(new Cloud);
  c->reserve(pts.size());
  for (const Vec3& p : pts) {
    const Vec3 q = p - origin;
    c->push_back(pcl::PointXYZ(float(q.x()), float(q.y()), float(q.z())));
  }
  return c;
}

Vec3 centroid(const std::vector<Vec3>& pts) {
  Vec3 s = Vec3::Zero();
  for (const Vec3& p : pts) s += p;
  return pts.empty() ? s : Vec3(s / double(pts.size()));
}

struct Plane {
  Vec3 normal = Vec3::UnitZ();
  Vec3 point = Vec3::Zero();
  double distance(const Vec3& p) const { return normal.dot(p - point); }
};

constexpr size_t kRansacPoints = 20000;

Plane ransac_plane(const std::vector<Vec3>& pts, double threshold, size_t* inliers) {
  if (pts.size() < 3) throw Error("cloud preparation", "a plane fit needs at least 3 points");
  const Vec3 origin = centroid(pts);
  // The plane is searched on an even subsample (RANSAC's cost is iterations x points), then refined by least
  // squares over its inliers among all the points.
  const size_t stride = std::max<size_t>(1, pts.size() / kRansacPoints);
  std::vector<Vec3> sample;
  for (size_t i = 0; i < pts.size(); i += stride) sample.push_back(pts[i]);
  using Model = pcl::SampleConsensusModelPlane<pcl::PointXYZ>;
  Model::Ptr model(new Model(to_pcl(sample, origin)));
  pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model);
  ransac.setDistanceThreshold(threshold);
  ransac.setMaxIterations(1000);
  if (!ransac.computeModel()) throw Error("cloud preparation", "RANSAC found no base plane");
  Eigen::VectorXf coeff;
  ransac.getModelCoefficients(coeff);
  Model::Ptr all(new Model(to_pcl(pts, origin)));
  pcl::Indices in;
  all->selectWithinDistance(coeff, threshold, in);
  if (in.size() < 3) throw Error("cloud preparation", "RANSAC found no base plane");
  Eigen::VectorXf refined;
  all->optimizeModelCoefficients(in, coeff, refined);  // least squares over the inliers
  Plane pl;
  pl.normal = Vec3(refined[0], refined[1], refined[2]);
  const double len = pl.normal.norm();
  if (!(len > 0)) throw Error("cloud preparation", "RANSAC returned a degenerate plane");
  pl.normal /= len;
  pl.point = origin - pl.normal * (double(refined[3]) / len);
  // The part stands on its base: most points must lie above the plane.
  size_t above = 0, below = 0;
  for (const Vec3& p : pts) {
    const double d = pl.distance(p);
    if (d > threshold) ++above;
    if (d < -threshold) ++below;
  }
  if (below > above) pl.normal = -pl.normal;
  if (inliers) *inliers = in.size();
  return pl;
}

Plane lowest_fit_plane(const std::vector<Vec3>& pts, double fraction, size_t* used) {
  if (pts.size() < 3) throw Error("cloud preparation", "a plane fit needs at least 3 points");
  const size_t k = std::clamp(size_t(double(pts.size()) * fraction), size_t(3), pts.size());
  std::vector<Vec3> low(pts);
  std::nth_element(low.begin(), low.begin() + (k - 1), low.end(), [](const Vec3& a, const Vec3& b) { return a.z() < b.z(); });
  low.resize(k);
  // Least squares plane: the eigenvector of the smallest eigenvalue of the covariance.
  Plane pl;
  pl.point = centroid(low);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : low) cov += (p - pl.point) * (p - pl.point).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  pl.normal = es.eigenvectors().col(0).normalized();
  if (pl.normal.z() < 0) pl.normal = -pl.normal;
  if (used) *used = k;
  return pl;
}

// The rigid transform that takes the plane's normal to +Z and the plane to z = 0.
Eigen::Matrix4d plane_to_xy(const Plane& pl) {
  const Eigen::Matrix3d rot = Eigen::Quaterniond::FromTwoVectors(pl.normal, Vec3::UnitZ()).toRotationMatrix();
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.topLeftCorner<3, 3>() = rot;
  t.topRightCorner<3, 1>() = -(rot * pl.point);
  return t;
}

std::vector<Vec3> remove_outliers(const std::vector<Vec3>& pts, int k, double stddev) {
  if (pts.size() <= size_t(k)) return pts;
  Cloud::Ptr in = to_pcl(pts, centroid(pts));
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
  sor.setInputCloud(in);
  sor.setMeanK(k);
  sor.setStddevMulThresh(stddev);
  pcl::Indices kept;
  sor.filter(kept);  // indices keep the points in double precision
  std::vector<Vec3> res;
  res.reserve(kept.size());
  for (auto i : kept) res.push_back(pts[size_t(i)]);
  return res;
}

void check_options(const CloudPrepOptions& o) {
  const std::string w = "cloud preparation";
  if (!o.transform.allFinite()) throw Error(w, "the transform holds a NaN or infinite number");
  if (o.orientation == Orientation::Transform) check_rigid(o.transform, w);
  if (!(o.plane_threshold > 0) || !std::isfinite(o.plane_threshold))
    throw Error(w, "the plane threshold must be a positive number of mm");
  if (!(o.lowest_fraction > 0 && o.lowest_fraction <= 1)) throw Error(w, "the lowest fraction must be in (0, 1]");
  if (o.remove_base && (o.orientation == Orientation::AsIs || o.orientation == Orientation::Transform))
    throw Error(w, "removing the base plane needs a fitted plane (RANSAC or lowest points)");
  if (!(o.voxel >= 0) || !std::isfinite(o.voxel)) throw Error(w, "the voxel leaf must be >= 0 mm");
  if (o.outlier_neighbours < 0) throw Error(w, "the outlier filter's neighbour count must be >= 0");
  if (!(o.outlier_stddev > 0) || !std::isfinite(o.outlier_stddev))
    throw Error(w, "the outlier filter's deviation multiplier must be a positive number");
  if (!(o.hole_cell >= 0) || !std::isfinite(o.hole_cell)) throw Error(w, "the hole cell must be >= 0 mm");
}

void report_density(const std::vector<Vec3>& pts, double hole_cell, CloudPrepReport& r) {
  Box3 box;
  for (const Vec3& p : pts) box.add(p);
  r.bbox = box;
  const Vec3 s = box.size();
  const CloudGrid grid(pts, auto_grid_cell(pts.size(), std::max(s.x() * s.y(), 1e-6)));
  r.mean_spacing = mean_spacing(grid);
  r.hole_cell = hole_cell > 0 ? hole_cell : auto_hole_cell(grid);
  const HoleMap holes(pts, r.hole_cell);
  r.hole_cell = holes.grid().cell();
  r.sampling_radius = sampling_radius(grid, holes.grid());
  r.grid_cells = holes.cells();
  r.empty_cells = holes.empty_cells();
  r.outside_cells = holes.outside_cells();
  r.holes = holes.holes();
}

}  // namespace

PointCloud prepare_cloud(const std::vector<Vec3>& input, const CloudPrepOptions& o, CloudPrepReport* report) {
  check_options(o);
  CloudPrepReport r;
  r.points_in = input.size();
  const double scale = mm_per_unit(o.units);
  std::vector<Vec3> pts;
  pts.reserve(input.size());
  for (const Vec3& p : input)
    if (p.allFinite()) pts.push_back(p * scale);
  r.dropped_nonfinite = input.size() - pts.size();
  if (pts.empty()) throw Error("cloud preparation", "no finite point in the cloud");

  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  bool have_plane = false;
  Plane plane;
  switch (o.orientation) {
    case Orientation::AsIs: r.orientation = "as is"; break;
    case Orientation::Transform: t = o.transform; r.orientation = "given transform"; break;
    case Orientation::Ransac:
      plane = ransac_plane(pts, o.plane_threshold, &r.plane_inliers);
      have_plane = true;
      r.orientation = "base plane by PCL RANSAC";
      break;
    case Orientation::LowestFit:
      plane = lowest_fit_plane(pts, o.lowest_fraction, &r.plane_inliers);
      have_plane = true;
      r.orientation = "base plane by least squares on the lowest points";
      break;
  }
  if (have_plane) t = plane_to_xy(plane);
  if (!t.isIdentity(0)) transform_points(t, pts);
  if (have_plane && o.remove_base) {
    const size_t before = pts.size();
    pts.erase(std::remove_if(pts.begin(), pts.end(), [&](const Vec3& p) { return std::abs(p.z()) <= o.plane_threshold; }),
              pts.end());
    r.removed_base = before - pts.size();
    if (pts.empty()) throw Error("cloud preparation", "nothing left after removing the base plane");
  }
  if (o.voxel > 0) pts = voxel_centroids(pts, o.voxel);
  r.after_voxel = pts.size();
  if (o.outlier_neighbours > 0) {
    const size_t before = pts.size();
    pts = remove_outliers(pts, o.outlier_neighbours, o.outlier_stddev);
    r.removed_outliers = before - pts.size();
  }
  if (pts.empty()) throw Error("cloud preparation", "no point left after the filters");
  if (o.origin_at_corner) {
    Box3 box;
    for (const Vec3& p : pts) box.add(p);
    const Vec3 shift(-box.min.x(), -box.min.y(), have_plane ? 0.0 : -box.min.z());
    for (Vec3& p : pts) p += shift;
    Eigen::Matrix4d s = Eigen::Matrix4d::Identity();
    s.topRightCorner<3, 1>() = shift;
    t = s * t;
  }
  r.transform = t;
  r.points_out = pts.size();
  if (report) report_density(pts, o.hole_cell, r);  // the density and hole maps cost time and only report
  PointCloud out;
  out.points = std::move(pts);
  out.recompute_bbox();
  if (report) *report = std::move(r);
  return out;
}

std::string format_prep_report(const CloudPrepReport& r) {
  std::ostringstream s;
  s << "points in: " << r.points_in << " (non-finite dropped: " << r.dropped_nonfinite << ")\n"
    << "orientation: " << r.orientation;
  if (r.plane_inliers) s << " (" << r.plane_inliers << " plane points)";
  s << "\nbase points removed: " << r.removed_base << "\nafter voxel filter: " << r.after_voxel
    << "\noutliers removed: " << r.removed_outliers << "\npoints out: " << r.points_out
    << "\nmean spacing: " << r.mean_spacing << " mm\nsampling radius: " << r.sampling_radius << " mm\nhole grid: " << r.grid_cells << " cells of " << r.hole_cell
    << " mm, " << r.empty_cells << " empty (" << r.outside_cells << " outside the part)\nholes: " << r.holes.size()
    << '\n';
  for (const Hole& h : r.holes)
    s << "  hole x " << h.box.min.x() << ".." << h.box.max.x() << " y " << h.box.min.y() << ".." << h.box.max.y()
      << ": " << h.cells << " cells, " << h.area << " mm², bridged at z " << h.lid_z << '\n';
  return s.str();
}

}  // namespace rosmill::core
