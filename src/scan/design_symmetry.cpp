#include "rosmill/scan/design_symmetry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>

#include <Eigen/Geometry>

#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/scan/near_surface_cells.hpp"
#include "rosmill/scan/thinning.hpp"

namespace rosmill::core::scan {

// The exact check of a motion refined onto the design: the share of points within the inlier distance and their RMS.
bool maps_onto_itself(const MeshDistance& distance, const std::vector<Vec3>& points, const Eigen::Matrix4d& motion,
                      const SymmetryOptions& o) {
  size_t inliers = 0;
  double sum_sq = 0;
  for (const Vec3& p : points) {
    SurfaceDistance d;
    if (!distance.query_within((motion * p.homogeneous()).head<3>(), o.inlier_distance, d)) continue;
    ++inliers;
    sum_sq += d.signed_distance * d.signed_distance;
  }
  return inliers >= o.min_share * double(points.size()) && std::sqrt(sum_sq / double(inliers)) <= o.tolerance;
}

namespace {

// With all three moments equal (a cube, a regular polyhedron) the principal axes are arbitrary, so the turns are
// sought about the normal of the design's largest flat area instead, and its turn-overs: a frame whose moments say
// that this axis is the free one.
PrincipalFrame frame_of_largest_flat(const Mesh& design, const Vec3& centroid) {
  // The area per normal direction, the normals rounded to a hundredth (about half a degree).
  std::map<std::array<long, 3>, std::pair<double, Vec3>> by_direction;
  for (size_t f = 0; f < design.faces.size(); ++f) {
    const Vec3& n = design.normals[f];
    auto& [area, normal] = by_direction[{std::lround(100 * n.x()), std::lround(100 * n.y()), std::lround(100 * n.z())}];
    area += design.areas[f];
    normal = n;
  }
  Vec3 normal = Vec3::UnitZ();
  double largest = 0;
  for (const auto& [key, flat] : by_direction)
    if (flat.first > largest && flat.second.squaredNorm() > 0.5) largest = flat.first, normal = flat.second;
  PrincipalFrame frame;
  frame.centroid = centroid;
  const Vec3 other = std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  frame.axes.col(0) = normal.cross(other).normalized();
  frame.axes.col(1) = normal.cross(frame.axes.col(0));
  frame.axes.col(2) = normal;
  frame.moments = Vec3(1, 1, 0);
  return frame;
}

}  // namespace

std::vector<Eigen::Matrix4d> design_symmetries(const Mesh& design, const SurfaceSample& sample,
                                               const PrincipalFrame& frame, const PlaneIcp& icp,
                                               const MeshDistance& distance, const SymmetryOptions& o, size_t limit) {
  constexpr size_t kPoints = 2000;     // design points a motion is scored on
  constexpr double kScored = 0.97;     // share near the surface that makes a motion worth refining
  constexpr size_t kMostRefined = 12;  // ICP refinements at most (an axisymmetric part scores everywhere)
  const std::vector<Vec3> points = thin_evenly(sample.points, kPoints);
  double radius = 0;  // the farthest point from the centroid: how far a turn moves a point
  for (const Vec3& p : points) radius = std::max(radius, (p - frame.centroid).norm());
  // Cells no finer than the sampling (every cell near the surface holds a sample) nor than 1/200 of the part.
  const double area = std::accumulate(design.areas.begin(), design.areas.end(), 0.0);
  const double cell = std::max(design.bbox.size().norm() / 200, std::sqrt(area / double(sample.points.size())));
  const NearSurfaceCells cells(sample.points, design.bbox, cell);
  // At this step the nearest motion to a symmetry moves no point by more than half a cell.
  const double step_deg = std::clamp(cell / radius * 180 / M_PI, 0.1, 10.0);
  const PrincipalFrame kept = near_equal_moments(frame.moments, o.moment_tolerance) == 3
                                  ? frame_of_largest_flat(design, frame.centroid)
                                  : frame;
  const std::vector<Eigen::Matrix4d> motions =
      principal_symmetry_probes(Eigen::Matrix4d::Identity(), kept, o.moment_tolerance, step_deg);

  // Motions that move the design's points by more than a few cells only: a smaller one is the identity's neighbour.
  const double least_deg = 4 * step_deg;
  std::vector<double> share(motions.size(), 0);
  for_each_index(size_t(0), motions.size(), [&](size_t i) {
    if (rotation_angle_deg(motions[i]) >= least_deg) share[i] = cells.share_near(points, motions[i]);
  });
  std::vector<size_t> order(motions.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return share[a] > share[b]; });

  std::vector<Eigen::Matrix4d> found, tried;
  const auto close_to = [&](const std::vector<Eigen::Matrix4d>& poses, const Eigen::Matrix4d& m) {
    return std::any_of(poses.begin(), poses.end(),
                       [&](const Eigen::Matrix4d& p) { return rotation_angle_deg(rigid_inverse(p) * m) < least_deg; });
  };
  for (size_t i : order) {
    if (share[i] < kScored || found.size() == limit || tried.size() == kMostRefined) break;
    if (close_to(tried, motions[i])) continue;
    tried.push_back(motions[i]);
    const Eigen::Matrix4d refined = icp.align(points, motions[i], 2 * cell, 30);
    if (rotation_angle_deg(refined) < least_deg || close_to(found, refined)) continue;
    if (maps_onto_itself(distance, points, refined, o)) found.push_back(refined);
  }
  return found;
}

}  // namespace rosmill::core::scan
