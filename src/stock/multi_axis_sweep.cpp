#include "rosmill/stock/multi_axis_sweep.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "rosmill/error.hpp"

namespace rosmill::core::stock {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTiny = 1e-12;
constexpr int kMaxSteps = 256;
constexpr long kMaxBins = 1L << 22;

// Intersects [lo, hi] with the z where a + b z >= 0 (b the slope); false once it is empty.
bool keep_nonnegative(double a, double b, double& lo, double& hi) {
  if (std::abs(b) < kTiny) {
    if (a < 0) return false;
  } else if (b > 0) {
    lo = std::max(lo, -a / b);
  } else {
    hi = std::min(hi, -a / b);
  }
  return lo <= hi;
}

// The z of the vertical line through q = (x, y, 0) within r of the segment [a, b] (a capsule: convex, so one
// interval), widened into [lo, hi].
void capsule_interval(const Vec3& q, const Vec3& a, const Vec3& b, double r, double& lo, double& hi) {
  for (const Vec3* c : {&a, &b}) {
    const double d2 = (q.head<2>() - c->head<2>()).squaredNorm();
    if (d2 <= r * r) {
      const double h = std::sqrt(r * r - d2);
      lo = std::min(lo, c->z() - h);
      hi = std::max(hi, c->z() + h);
    }
  }
  const Vec3 d = b - a;
  const double length = d.norm();
  if (length < kTiny) return;
  const Vec3 u = d / length;
  const Vec3 w0 = q - a;
  const Vec3 w0p = w0 - w0.dot(u) * u, ezp = Vec3::UnitZ() - u.z() * u;
  // |w0p + z ezp|^2 <= r^2, with the foot of the perpendicular on the segment: 0 <= w0.u + z u.z <= length.
  double zlo = -kInf, zhi = kInf;
  const double qa = ezp.squaredNorm(), qb = w0p.dot(ezp), qc = w0p.squaredNorm() - r * r;
  if (qa < kTiny) {
    if (qc > 0) return;
  } else {
    const double disc = qb * qb - qa * qc;
    if (disc < 0) return;
    const double s = std::sqrt(disc);
    zlo = (-qb - s) / qa;
    zhi = (-qb + s) / qa;
  }
  if (!keep_nonnegative(w0.dot(u), u.z(), zlo, zhi)) return;
  if (!keep_nonnegative(length - w0.dot(u), -u.z(), zlo, zhi)) return;
  lo = std::min(lo, zlo);
  hi = std::max(hi, zhi);
}

// The unit normal of the triangle's plane, or zero for a triangle with (almost) no area.
Vec3 plane_normal(const SweptTriangle& t) {
  const Vec3 n = (t.v1 - t.v0).cross(t.v2 - t.v0);
  const double scale = (t.v1 - t.v0).squaredNorm() + (t.v2 - t.v0).squaredNorm() + (t.v2 - t.v1).squaredNorm();
  return n.norm() > 1e-9 * scale ? Vec3(n.normalized()) : Vec3::Zero();
}

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double l2 = d.squaredNorm();
  const double s = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + s * d)).norm();
}

Vec3 normalised(const Vec3& v, const char* what) {
  const double n = v.norm();
  if (!(n > 1e-9) || !std::isfinite(n)) throw Error("multi-axis move", std::string(what) + " is not a direction");
  return v / n;
}

}  // namespace

bool vertical_interval(const SweptTriangle& t, double x, double y, double& lo, double& hi) {
  const Vec3 q(x, y, 0);
  lo = kInf;
  hi = -kInf;
  capsule_interval(q, t.v0, t.v1, t.r, lo, hi);
  capsule_interval(q, t.v1, t.v2, t.r, lo, hi);
  capsule_interval(q, t.v2, t.v0, t.r, lo, hi);
  const Vec3 n = plane_normal(t);
  if (n != Vec3::Zero()) {
    // The slab over the triangle: within r of its plane, and inside each edge (m, the edge's inward normal in the
    // plane, is perpendicular to n, so the line's projection onto the plane is inside where q + z ez is).
    double zlo = -kInf, zhi = kInf;
    const Vec3 w0 = q - t.v0;
    bool in = keep_nonnegative(t.r + w0.dot(n), n.z(), zlo, zhi) && keep_nonnegative(t.r - w0.dot(n), -n.z(), zlo, zhi);
    const Vec3* v[3] = {&t.v0, &t.v1, &t.v2};
    for (int e = 0; in && e < 3; ++e) {
      const Vec3& a = *v[e];
      const Vec3 m = n.cross(*v[(e + 1) % 3] - a);
      in = keep_nonnegative((q - a).dot(m), m.z(), zlo, zhi);
    }
    if (in) {
      lo = std::min(lo, zlo);
      hi = std::max(hi, zhi);
    }
  }
  return lo <= hi;
}

double distance_to_triangle(const SweptTriangle& t, const Vec3& p) {
  double d = std::min(
      {distance_to_segment(p, t.v0, t.v1), distance_to_segment(p, t.v1, t.v2), distance_to_segment(p, t.v2, t.v0)});
  const Vec3 n = plane_normal(t);
  if (n == Vec3::Zero()) return d;
  const Vec3* v[3] = {&t.v0, &t.v1, &t.v2};
  for (int e = 0; e < 3; ++e)
    if ((p - *v[e]).dot(n.cross(*v[(e + 1) % 3] - *v[e])) < 0) return d;  // outside an edge: an edge is nearest
  return std::min(d, std::abs((p - t.v0).dot(n)));
}

void MultiAxisSweep::add_move(const Vec3& tip0, const Vec3& axis0, const Vec3& tip1, const Vec3& axis1, double r,
                              double flutes, double sagitta, uint32_t move) {
  if (!tip0.allFinite() || !tip1.allFinite()) throw Error("multi-axis move", "a position is not finite");
  if (!(r > 0) || !(sagitta > 0)) throw Error("multi-axis move", "the ball radius and the sagitta must be > 0 mm");
  const Vec3 a0 = normalised(axis0, "the tool axis at its start"), a1 = normalised(axis1, "the tool axis at its end");
  const double reach =
      std::max(0.0, flutes - 2 * r);  // the top cap's centre above the ball's: its apex at the flutes' end
  const auto pose = [&](double s, Vec3& centre, Vec3& top) {
    const Vec3 tip = tip0 + s * (tip1 - tip0);
    const Vec3 axis = (a0 + s * (a1 - a0)).normalized();
    centre = tip + r * axis;
    top = centre + reach * axis;
  };
  // A turn of theta moves the flute top on an arc of radius at most `flutes` about the tip's line, whose chord
  // strays flutes * theta^2 / 8 from it: steps of at most sqrt(8 sagitta / flutes) radians.
  const double turn = std::acos(std::clamp(a0.dot(a1), -1.0, 1.0));
  const double most = std::sqrt(8 * sagitta / std::max(flutes, r));
  const int steps = std::clamp(static_cast<int>(std::ceil(turn / most)), 1, kMaxSteps);
  Vec3 c0, t0;
  pose(0, c0, t0);
  for (int k = 1; k <= steps; ++k) {
    Vec3 c1, t1;
    pose(double(k) / steps, c1, t1);
    for (const auto& [p, q, s] : {std::tuple{c0, c1, t0}, std::tuple{t0, c1, t1}}) {
      SweptTriangle t{p, q, s, r, move, {}, {}};
      t.lo = p.cwiseMin(q).cwiseMin(s).array() - r;
      t.hi = p.cwiseMax(q).cwiseMax(s).array() + r;
      triangles_.push_back(t);
    }
    c0 = c1;
    t0 = t1;
  }
}

void MultiAxisSweep::index() {
  first_.clear();
  items_.clear();
  nx_ = ny_ = 0;
  if (triangles_.empty()) return;
  Vec2 lo = Vec2::Constant(kInf), hi = Vec2::Constant(-kInf);
  for (const SweptTriangle& t : triangles_) {
    lo = lo.cwiseMin(t.lo.head<2>());
    hi = hi.cwiseMax(t.hi.head<2>());
  }
  lo.array() -= kMaxGrow;
  hi.array() += kMaxGrow;
  origin_ = lo;
  bin_ = 2.0;
  const Vec2 size = hi - lo;
  while ((std::floor(size.x() / bin_) + 1) * (std::floor(size.y() / bin_) + 1) > double(kMaxBins)) bin_ *= 2;
  nx_ = long(size.x() / bin_) + 1;
  ny_ = long(size.y() / bin_) + 1;
  const auto span = [&](const SweptTriangle& t, long& i0, long& i1, long& j0, long& j1) {
    i0 = std::clamp(long((t.lo.x() - kMaxGrow - origin_.x()) / bin_), 0L, nx_ - 1);
    i1 = std::clamp(long((t.hi.x() + kMaxGrow - origin_.x()) / bin_), 0L, nx_ - 1);
    j0 = std::clamp(long((t.lo.y() - kMaxGrow - origin_.y()) / bin_), 0L, ny_ - 1);
    j1 = std::clamp(long((t.hi.y() + kMaxGrow - origin_.y()) / bin_), 0L, ny_ - 1);
  };
  // Two passes, counting then filling: each bin's triangles in the order they were added.
  first_.assign(size_t(nx_ * ny_) + 1, 0);
  for (const SweptTriangle& t : triangles_) {
    long i0, i1, j0, j1;
    span(t, i0, i1, j0, j1);
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) ++first_[size_t(j * nx_ + i) + 1];
  }
  for (size_t b = 1; b < first_.size(); ++b) first_[b] += first_[b - 1];
  items_.resize(first_.back());
  std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
  for (uint32_t k = 0; k < triangles_.size(); ++k) {
    long i0, i1, j0, j1;
    span(triangles_[k], i0, i1, j0, j1);
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) items_[fill[size_t(j * nx_ + i)]++] = k;
  }
}

long MultiAxisSweep::bin_of(double x, double y) const {
  if (nx_ == 0) return -1;
  const double u = (x - origin_.x()) / bin_, v = (y - origin_.y()) / bin_;
  if (!(u >= 0 && v >= 0 && u < double(nx_) && v < double(ny_))) return -1;
  return long(v) * nx_ + long(u);
}

bool MultiAxisSweep::reaches(const Vec3& p, double grow) const {
  grow = std::clamp(grow, 0.0, kMaxGrow);
  const long b = bin_of(p.x(), p.y());
  if (b < 0) return false;
  for (uint32_t i = first_[size_t(b)]; i < first_[size_t(b) + 1]; ++i) {
    const SweptTriangle& t = triangles_[items_[i]];
    if (((p - t.lo).array() < -grow).any() || ((p - t.hi).array() > grow).any()) continue;
    if (distance_to_triangle(t, p) <= t.r + grow) return true;
  }
  return false;
}

double MultiAxisSweep::depth(const Vec3& p, uint32_t* move) const {
  double best = -kInf;
  at(p.x(), p.y(), [&](size_t k) {
    const SweptTriangle& t = triangles_[k];
    if (p.z() < t.lo.z() || p.z() > t.hi.z()) return;
    const double d = t.r - distance_to_triangle(t, p);
    if (d > best) {
      best = d;
      if (move) *move = t.move;
    }
  });
  return best;
}

size_t MultiAxisSweep::bytes() const {
  return triangles_.capacity() * sizeof(SweptTriangle) + (first_.capacity() + items_.capacity()) * sizeof(uint32_t);
}

}  // namespace rosmill::core::stock
