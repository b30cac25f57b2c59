#include "cloud_route.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::cloud_detail {

void ProgressRange::operator()(double f) const {
  if (p_ && !p_(lo_ + (hi_ - lo_) * std::clamp(f, 0.0, 1.0))) throw Error("plan", "cancelled");
}

namespace {

void add_segment(Route& r, const Vec2& a, const Vec2& b, double step, bool include_start) {
  const double len = (b - a).norm();
  const size_t n = std::max<size_t>(1, size_t(std::ceil(len / step)));
  for (size_t i = include_start ? 0 : 1; i <= n; ++i) {
    r.xy.push_back(a + (b - a) * (double(i) / double(n)));
    r.corner.push_back(i == 0 || i == n);
  }
}

}  // namespace

void box_extent(const Box3& box, double angle_deg, double& u0, double& u1, double& v0, double& v1) {
  const double a = angle_deg * M_PI / 180.0;
  const Vec2 u(std::cos(a), std::sin(a)), v(-std::sin(a), std::cos(a));
  u0 = v0 = INFINITY;
  u1 = v1 = -INFINITY;
  for (double x : {box.min.x(), box.max.x()})
    for (double y : {box.min.y(), box.max.y()}) {
      const Vec2 p(x, y);
      u0 = std::min(u0, p.dot(u));
      u1 = std::max(u1, p.dot(u));
      v0 = std::min(v0, p.dot(v));
      v1 = std::max(v1, p.dot(v));
    }
}

Route zigzag_route(double angle_deg, double u0, double u1, const std::vector<double>& v, double step) {
  if (!(step > 0)) throw Error("plan", "sample step must be positive");
  const double a = angle_deg * M_PI / 180.0;
  const Vec2 du(std::cos(a), std::sin(a)), dv(-std::sin(a), std::cos(a));
  Route r;
  for (size_t j = 0; j < v.size(); ++j) {
    const bool forward = j % 2 == 0;
    const Vec2 start = du * (forward ? u0 : u1) + dv * v[j];
    const Vec2 end = du * (forward ? u1 : u0) + dv * v[j];
    r.line_start.push_back(uint32_t(r.xy.size()));
    if (j > 0) add_segment(r, r.xy.back(), start, step, false);  // the step across, at the lines' ends
    add_segment(r, start, end, step, j == 0);
  }
  return r;
}

std::vector<double> route_drops(const CloudSurface& s, const Cutter& cutter, const Route& route,
                                const ProgressRange& progress) {
  const size_t n = route.xy.size();
  std::vector<double> z(n);
  std::vector<Drop> drops;
  const size_t chunk = 65536;
  drops.resize(std::min(n, chunk));
  for (size_t i = 0; i < n; i += chunk) {
    const size_t m = std::min(chunk, n - i);
    s.drop_many(cutter, route.xy.data() + i, m, drops.data());
    for (size_t k = 0; k < m; ++k) z[i + k] = drops[k].z;
    progress(double(i + m) / double(n));
  }
  return z;
}

namespace {

// Splits [a, b] at the sample of largest |ε| while it exceeds eps (the seed's binary tree of buffer points).
size_t refine(const std::vector<Vec3>& cl, size_t a, size_t b, double eps, std::vector<uint32_t>& out) {
  if (b <= a + 1) return 0;
  const Vec3& p1 = cl[a];
  const Vec3& p2 = cl[b];
  const Vec2 d = (p2 - p1).head<2>();
  const double len2 = d.squaredNorm();
  double worst = 0.0;
  size_t at = a;
  for (size_t i = a + 1; i < b; ++i) {
    // Pd: the chord's height above Pi's plan position (seed: Pd.z = P1.z - (P1.x - Pi.x)(P1.z - P2.z)/(P1.x - P2.x),
    // with the distance along the line in place of x so any raster direction works).
    const double t = len2 > 0 ? std::clamp((cl[i] - p1).head<2>().dot(d) / len2, 0.0, 1.0) : 0.0;
    const double eps_i = std::abs(cl[i].z() - (p1.z() + t * (p2.z() - p1.z())));
    if (eps_i > worst) {
      worst = eps_i;
      at = i;
    }
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

void drop_collinear(std::vector<Vec3>& pts) {
  if (pts.size() < 3) return;
  std::vector<Vec3> out;
  out.reserve(pts.size());
  out.push_back(pts[0]);
  for (size_t i = 1; i + 1 < pts.size(); ++i) {
    const Vec3 a = pts[i] - out.back(), b = pts[i + 1] - pts[i];
    const double la = a.norm(), lb = b.norm();
    if (la < 1e-12) continue;  // duplicate
    if (lb > 1e-12 && a.cross(b).norm() <= 1e-9 * la * lb && a.dot(b) > 0) continue;
    out.push_back(pts[i]);
  }
  if ((pts.back() - out.back()).norm() > 1e-12 || out.size() == 1) out.push_back(pts.back());
  pts.swap(out);
}

}  // namespace rosmill::cloud_detail
