#include "rosmill/testing/synthetic_scan.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "rosmill/scan/surface_sample.hpp"

namespace rosmill::core::synthetic {

PointCloud synthetic_scan(const Mesh& design, const std::vector<Vec3>& sensors, size_t samples, double noise,
                          uint64_t seed) {
  const scan::SurfaceSample s = scan::sample_surface(design, samples, seed);
  std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ull);
  std::normal_distribution<double> gauss(0.0, noise);
  PointCloud cloud;
  for (size_t i = 0; i < s.points.size(); ++i) {
    bool seen = false;
    for (const Vec3& sensor : sensors) seen = seen || s.normals[i].dot(sensor - s.points[i]) > 0;
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

std::vector<Vec3> sensors_above(const Mesh& design, int oblique, double distance) {
  const Vec3 centre = (design.bbox.min + design.bbox.max) / 2;
  std::vector<Vec3> out{centre + Vec3(0, 0, distance)};
  for (int i = 0; i < oblique; ++i) {
    const double a = 2 * M_PI * i / oblique;
    out.push_back(centre + distance * Vec3(std::cos(a), std::sin(a), 1).normalized());
  }
  return out;
}

}  // namespace rosmill::core::synthetic
