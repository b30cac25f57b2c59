#include "cloud_route.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/cloud/cloud_sweep.hpp"
#include "rosmill/error.hpp"

namespace rosmill::cloud_detail {

void ProgressRange::operator()(double f) const {
  if (p_ && !p_(lo_ + (hi_ - lo_) * std::clamp(f, 0.0, 1.0))) throw Error("plan", "cancelled");
}

namespace {

size_t segment_steps(const Vec2& a, const Vec2& b, double step) {
  return std::max<size_t>(1, size_t(std::ceil((b - a).norm() / step)));
}

void add_segment(const Vec2& a, const Vec2& b, double step, bool include_start, std::vector<Vec2>& xy,
                 std::vector<uint8_t>& corner) {
  const size_t n = segment_steps(a, b, step);
  for (size_t i = include_start ? 0 : 1; i <= n; ++i) {
    xy.push_back(a + (b - a) * (double(i) / double(n)));
    corner.push_back(i == 0 || i == n);
  }
}

}  // namespace

Zigzag::Zigzag(double angle_deg, double u0, double u1, std::vector<double> v, double step)
    : u0_(u0), u1_(u1), step_(step), v_(std::move(v)) {
  if (!(step > 0) || !std::isfinite(step)) throw Error("plan", "sample step must be a positive number");
  const double a = angle_deg * M_PI / 180.0;
  du_ = Vec2(std::cos(a), std::sin(a));
  dv_ = Vec2(-std::sin(a), std::cos(a));
}

void Zigzag::samples(size_t j, std::vector<Vec2>& xy, std::vector<uint8_t>& corner) const {
  xy.clear();
  corner.clear();
  const bool forward = j % 2 == 0;
  const Vec2 start = at(forward ? u0_ : u1_, v_[j]), end = at(forward ? u1_ : u0_, v_[j]);
  if (j > 0) {
    const Vec2 prev_end = at(forward ? u0_ : u1_, v_[j - 1]);  // the previous line ran the other way
    xy.push_back(prev_end);
    corner.push_back(1);
    add_segment(prev_end, start, step_, false, xy, corner);
  }
  add_segment(start, end, step_, j == 0, xy, corner);
}

size_t Zigzag::sample_count(size_t j) const {
  const size_t line = segment_steps(at(u0_, 0), at(u1_, 0), step_);
  if (j == 0) return line + 1;
  return segment_steps(at(0, v_[j - 1]), at(0, v_[j]), step_) + line;
}

Route whole_route(const Zigzag& z) {
  Route r;
  size_t n = 0;
  for (size_t j = 0; j < z.lines(); ++j) n += z.sample_count(j);
  r.xy.reserve(n);
  r.corner.reserve(n);
  std::vector<Vec2> xy;
  std::vector<uint8_t> corner;
  for (size_t j = 0; j < z.lines(); ++j) {
    z.samples(j, xy, corner);
    const size_t from = j > 0 ? 1 : 0;
    r.xy.insert(r.xy.end(), xy.begin() + long(from), xy.end());
    r.corner.insert(r.corner.end(), corner.begin() + long(from), corner.end());
  }
  r.lines = z.lines();
  return r;
}

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

size_t checked_move(const CloudSurface& s, const Cutter& cutter, double delta, double t, const Vec3& a,
                    const Vec3& b, std::vector<Vec3>& out, int depth) {
  const Vec3 lift(0, 0, delta);
  const SweepHit hit = sweep_depth(s, cutter, a - lift, b - lift, t);
  if (hit.depth <= t) {
    out.push_back(b);
    return 0;
  }
  const Vec2 m = a.head<2>() + (b - a).head<2>() * hit.at;
  if (depth >= 40 || (b - a).head<2>().norm() < 1e-4) {
    // The CL jumps here (a point met by the cutter's side): go up first or come down last.
    out.push_back(b.z() > a.z() ? Vec3(a.x(), a.y(), b.z()) : Vec3(b.x(), b.y(), a.z()));
    out.push_back(b);
    return 1;
  }
  const Vec3 mid(m.x(), m.y(), std::max(s.drop(cutter, m.x(), m.y()).z, s.bounds().min.z()) + delta);  // the floor
  const size_t n = 1 + checked_move(s, cutter, delta, t, a, mid, out, depth + 1);
  return n + checked_move(s, cutter, delta, t, mid, b, out, depth + 1);
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
