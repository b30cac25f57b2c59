// Cloud preparation, the first step of Muslimin et al.'s direct toolpath generation: bring a scan into the
// workpiece frame before planning.
//
//   1. NaN and infinite points dropped; coordinates scaled to millimetres.
//   2. Orientation: the machined surface faces +Z. Either a given 4x4 transform (e.g. from tf2, in the input's
//      units after scaling: millimetres), or a fitted base plane:
//        Ransac      - PCL RANSAC plane fit over the whole cloud (the largest plane: the table or the part's base);
//                      the normal is flipped so most points lie above it.
//        LowestFit   - least squares (PCA) plane through the lowest `lowest_fraction` of the points along the
//                      current Z: for clouds that are already roughly upright.
//      The plane's normal becomes +Z and the plane z = 0.
//   3. Program origin at the stock corner: x, y at the minimum of the cloud's plan-view box; z = 0 at the base
//      plane (with a fit) or at the cloud's lowest point (no fit), so every point has z >= 0 up to noise.
//   4. Filters: voxel downsampling (centroid per voxel, voxel_grid.hpp) and PCL's statistical outlier removal.
//   5. A report: counts at each step, mean spacing, holes (enclosed empty cells of a plan-view grid).
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rosmill/cloud/cloud_holes.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/units.hpp"

namespace rosmill::core {

enum class Orientation { AsIs, Transform, Ransac, LowestFit };

struct CloudPrepOptions {
  Units units = Units::Millimetre;  // units of the incoming coordinates
  Orientation orientation = Orientation::AsIs;
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();  // for Orientation::Transform (applied after scaling)
  double plane_threshold = 0.5;     // mm: RANSAC inlier distance
  double lowest_fraction = 0.05;    // LowestFit: share of the points used
  bool remove_base = false;         // drop the fitted base plane's inliers (a table around the part)
  bool origin_at_corner = true;     // move the program origin to the stock corner
  double voxel = 0.0;               // mm: voxel grid leaf size; 0 = off
  int outlier_neighbours = 0;       // StatisticalOutlierRemoval mean-k; 0 = off
  double outlier_stddev = 2.0;      // its standard-deviation multiplier
  double hole_cell = 0.0;           // mm; 0: auto_hole_cell()
};

struct CloudPrepReport {
  size_t points_in = 0;
  size_t dropped_nonfinite = 0;
  size_t removed_base = 0;
  size_t after_voxel = 0;
  size_t removed_outliers = 0;
  size_t points_out = 0;
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();  // input (scaled to mm) -> workpiece frame
  std::string orientation;       // how the frame was found
  size_t plane_inliers = 0;
  double mean_spacing = 0.0;     // mm, nearest-neighbour mean
  double sampling_radius = 0.0;  // mm, plan view (cloud_grid.hpp): the support discs' size before the cutter's share
  double hole_cell = 0.0;
  size_t grid_cells = 0, empty_cells = 0, outside_cells = 0;
  std::vector<Hole> holes;       // enclosed empty regions
  Box3 bbox;
};

// `points` may hold NaN or infinite coordinates (an organised cloud); they are dropped and counted. Throws Error
// on a bad option (a transform that is not rigid, a negative leaf, ...) or when no point is left.
PointCloud prepare_cloud(const std::vector<Vec3>& points, const CloudPrepOptions& options,
                         CloudPrepReport* report = nullptr);
inline PointCloud prepare_cloud(const PointCloud& cloud, const CloudPrepOptions& options,
                                CloudPrepReport* report = nullptr) {
  return prepare_cloud(cloud.points, options, report);
}

// The report as text, one fact a line (for the command line and logs).
std::string format_prep_report(const CloudPrepReport& r);

}  // namespace rosmill::core
