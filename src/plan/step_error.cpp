#include "rosmill/plan/step_error.hpp"

#include <algorithm>
#include <cmath>

namespace rosmill::core {

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

}  // namespace rosmill::core

namespace rosmill::core {

size_t checked_move(const Surface& s, const PlanFrame& f, const Vec3& a, const Vec3& b, std::vector<Vec3>& out,
                    int depth) {
  const Vec3 lift(0, 0, f.allowance);
  const SweepHit hit = s.sweep(f.drop_cutter, a - lift, b - lift, f.tolerance);
  if (hit.depth <= f.tolerance) {
    out.push_back(b);
    return 0;
  }
  if (depth >= 40 || (b - a).head<2>().norm() < 1e-4) {
    // The CL jumps here (the surface met by the cutter's side): go up first or come down last.
    out.push_back(b.z() > a.z() ? Vec3(a.x(), a.y(), b.z()) : Vec3(b.x(), b.y(), a.z()));
    out.push_back(b);
    return 1;
  }
  const Vec2 m = a.head<2>() + (b - a).head<2>() * hit.at;
  const Vec3 mid(m.x(), m.y(), cl_height(s, f, m.x(), m.y()));
  const size_t n = 1 + checked_move(s, f, a, mid, out, depth + 1);
  return n + checked_move(s, f, mid, b, out, depth + 1);
}

double step_error_spacing(const PlanFrame& f) {
  const double R = f.cutter.radius();
  return std::clamp(std::sqrt(4 * R * f.tolerance), kMinSampleStep, 0.5 * R);
}

void sample_step_error(const Surface& s, const PlanFrame& f, const Vec2& a, const Vec2& b, std::vector<Vec3>& out,
                       StepErrorCounts& counts) {
  const double h = step_error_spacing(f), R = f.cutter.radius();
  const size_t n = std::max<size_t>(1, size_t(std::ceil((b - a).norm() / h)));
  std::vector<Vec2> xy(n + 1);
  for (size_t i = 0; i <= n; ++i) xy[i] = a + (b - a) * (double(i) / double(n));
  std::vector<Drop> drops(n + 1);
  s.drop_many(f.drop_cutter, xy.data(), n + 1, drops.data());
  // Never below the floor (the part's lowest point): a ball that touches the last of the surface with its side
  // would otherwise hang its tip below it, beyond the part.
  std::vector<Vec3> cl(n + 1);
  for (size_t i = 0; i <= n; ++i)
    cl[i] = Vec3(xy[i].x(), xy[i].y(), std::max(drops[i].z, f.part.min.z()) + f.allowance);
  std::vector<uint8_t> corner(n + 1, 0);
  corner[0] = corner[n] = 1;
  std::vector<uint32_t> kept;
  counts.samples += n + 1;
  counts.buffers += buffer_points(cl, corner, 0, n, 2 * R, 0.5 * f.tolerance, kept);
  out.push_back(cl[kept[0]]);
  for (size_t m = 1; m < kept.size(); ++m) counts.checked += checked_move(s, f, cl[kept[m - 1]], cl[kept[m]], out);
}

}  // namespace rosmill::core
