#include "rosmill/testing/synthetic_scan.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "rosmill/scan/surface_sample.hpp"

namespace rosmill::core::synthetic {

PointCloud synthetic_scan(const Mesh& design, const std::vector<Vec3>& sensors, size_t samples, double noise,
                          uint64_t seed, double max_incidence_deg) {
  const double least_cosine = std::cos(max_incidence_deg * M_PI / 180);
  const scan::SurfaceSample s = scan::sample_surface(design, samples, seed);
  std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ull);
  std::normal_distribution<double> gauss(0.0, noise);
  PointCloud cloud;
  for (size_t i = 0; i < s.points.size(); ++i) {
    bool seen = false;
    for (const Vec3& sensor : sensors) {
      const Vec3 to = sensor - s.points[i];
      seen = seen || (s.normals[i].dot(to) > 0 && (max_incidence_deg >= 90 || s.normals[i].dot(to) >= least_cosine * to.norm()));
    }
    if (!seen) continue;
    cloud.points.push_back(s.points[i] + Vec3(gauss(rng), gauss(rng), gauss(rng)));
  }
  cloud.recompute_bbox();
  return cloud;
}

Eigen::Matrix4d random_rigid(std::mt19937_64& rng, double max_translation) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-max_translation, max_translation);
  Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  q.normalize();
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.topLeftCorner<3, 3>() = q.toRotationMatrix();
  for (int i = 0; i < 3; ++i) t(i, 3) = uniform(rng);
  return t;
}

Eigen::Matrix4d nudge(double mm, double deg, const Vec3& axis) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.topLeftCorner<3, 3>() = Eigen::AngleAxisd(deg * M_PI / 180, axis.normalized()).toRotationMatrix();
  t.topRightCorner<3, 1>() = mm * axis.normalized();
  return t;
}

double box_corner_error(const Mesh& design, const Eigen::Matrix4d& error) {
  double worst = 0;
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1 ? design.bbox.max : design.bbox.min).x(), (c & 2 ? design.bbox.max : design.bbox.min).y(),
                      (c & 4 ? design.bbox.max : design.bbox.min).z());
    const Vec3 moved = error.topLeftCorner<3, 3>() * corner + error.topRightCorner<3, 1>();
    worst = std::max(worst, (moved - corner).norm());
  }
  return worst;
}

std::vector<Vec3> sensors_above(const Mesh& design, int oblique, double distance) {
  const Vec3 centre = (design.bbox.min + design.bbox.max) / 2;
  std::vector<Vec3> out{centre + Vec3(0, 0, distance)};
  for (int i = 0; i < oblique; ++i) {
    const double a = 2 * M_PI * i / oblique;
    out.push_back(centre + distance * Vec3(std::cos(a), std::sin(a), 1).normalized());
  }
  return out;
}

Eigen::Matrix4d sensor_pose(const Vec3& position, const Vec3& target) {
  const Vec3 z = (target - position).normalized();
  const Vec3 x = z.cross(Vec3::UnitZ()).norm() > 1e-6 ? Vec3(z.cross(Vec3::UnitZ()).normalized()) : Vec3::UnitX();
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.block<3, 1>(0, 0) = x;
  t.block<3, 1>(0, 1) = z.cross(x);
  t.block<3, 1>(0, 2) = z;
  t.block<3, 1>(0, 3) = position;
  return t;
}

}  // namespace rosmill::core::synthetic
