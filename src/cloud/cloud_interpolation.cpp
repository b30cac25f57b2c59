#include "rosmill/cloud/cloud_interpolation.hpp"

#include <algorithm>
#include <cmath>

namespace rosmill {

double step_error(const Vec3& p1, const Vec3& p2, const Vec3& pi) {
  const Vec2 d = (p2 - p1).head<2>();
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((pi - p1).head<2>().dot(d) / len2, 0.0, 1.0) : 0.0;
  return pi.z() - (p1.z() + t * (p2.z() - p1.z()));
}

namespace {

// Splits [a, b] at the sample of largest |ε| while it exceeds eps.
size_t refine(const std::vector<Vec3>& cl, size_t a, size_t b, double eps, std::vector<uint32_t>& out) {
  if (b <= a + 1) return 0;
  double worst = 0.0;
  size_t at = a;
  for (size_t i = a + 1; i < b; ++i) {
    const double e = std::abs(step_error(cl[a], cl[b], cl[i]));
    if (e > worst) worst = e, at = i;
  }
  if (worst <= eps) return 0;
  size_t n = 1 + refine(cl, a, at, eps, out);
  out.push_back(uint32_t(at));
  return n + refine(cl, at, b, eps, out);
}

}  // namespace

size_t buffer_points(const std::vector<Vec3>& cl, const std::vector<uint8_t>& corner, size_t first, size_t last,
                     double interval, double eps, std::vector<uint32_t>& kept) {
  size_t buffers = 0;
  kept.push_back(uint32_t(first));
  size_t prev = first;
  double run = 0.0;
  for (size_t i = first + 1; i <= last; ++i) {
    run += (cl[i] - cl[i - 1]).head<2>().norm();
    if (i == last || corner[i] || run >= interval - 1e-9) {
      buffers += refine(cl, prev, i, eps, kept);
      kept.push_back(uint32_t(i));
      prev = i;
      run = 0.0;
    }
  }
  return buffers;
}

}  // namespace rosmill
