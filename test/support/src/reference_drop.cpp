#include "rosmill/testing/reference_drop.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace rosmill::core {
namespace {

constexpr double kNothing = -std::numeric_limits<double>::infinity();
constexpr double kGolden = 0.61803398874989485;

// The cutter's side view, written from the shape's definition: a flat bottom of radius R - r, then a quarter
// circle of radius r up to the full radius R.
struct Profile {
  double R = 0, r = 0;
  explicit Profile(const Cutter& c) : R(0.5 * c.diameter) {
    if (c.type == CutterType::BallEnd) r = R;
    else if (c.type == CutterType::BullNose) r = std::min(c.corner_radius, R);
  }
  double height(double d) const {
    const double e = std::min(d - (R - r), r);
    return e <= 0 ? 0.0 : r - std::sqrt(r * r - e * e);
  }
  // dh/dd, for d < R.
  double slope(double d) const {
    const double e = d - (R - r);
    return e <= 0 ? 0.0 : e / std::sqrt(r * r - e * e);
  }
};

// Smallest value of a convex f over [lo, hi] and where it is.
template <class F>
std::pair<double, double> golden_min(const F& f, double lo, double hi) {
  std::pair<double, double> best = std::min(std::make_pair(f(lo), lo), std::make_pair(f(hi), hi));
  double a = lo, b = hi;
  double x1 = b - kGolden * (b - a), x2 = a + kGolden * (b - a);
  double f1 = f(x1), f2 = f(x2);
  best = std::min({best, std::make_pair(f1, x1), std::make_pair(f2, x2)});
  for (int it = 0; it < 200 && b - a > 1e-15; ++it) {
    if (f1 > f2) {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + kGolden * (b - a);
      f2 = f(x2);
    } else {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - kGolden * (b - a);
      f1 = f(x1);
    }
    best = std::min({best, std::make_pair(f1, x1), std::make_pair(f2, x2)});
  }
  return best;
}

// Largest value of a concave f over [lo, hi]: the smallest of -f.
template <class F>
double golden_max(const F& f, double lo, double hi) {
  if (!(hi > lo)) return std::max(f(lo), f(hi));
  return -golden_min([&](double x) { return -f(x); }, lo, hi).first;
}

// The end of the feasible interval between a feasible s_in and an infeasible s_out, by bisection.
template <class Feasible>
double feasible_end(const Feasible& feasible, double s_in, double s_out) {
  if (feasible(s_out)) return s_out;
  for (int it = 0; it < 200 && std::abs(s_out - s_in) > 1e-16; ++it) {
    const double m = 0.5 * (s_in + s_out);
    if (m == s_in || m == s_out) break;
    (feasible(m) ? s_in : s_out) = m;
  }
  return s_in;
}

double bbox_distance(const Vec3& a, const Vec3& b, const Vec3& c, double x, double y) {
  const double dx = std::max({0.0, std::min({a.x(), b.x(), c.x()}) - x, x - std::max({a.x(), b.x(), c.x()})});
  const double dy = std::max({0.0, std::min({a.y(), b.y(), c.y()}) - y, y - std::max({a.y(), b.y(), c.y()})});
  return std::sqrt(dx * dx + dy * dy);
}

}  // namespace

double reference_triangle_drop(const Cutter& cutter, double x, double y, const Vec3& A, const Vec3& B,
                               const Vec3& C) {
  const Profile pr(cutter);
  const double R2 = pr.R * pr.R;
  // Horizontal offset of p(s, t) from the axis: q0 + s u + t w.
  const Vec2 q0(A.x() - x, A.y() - y), u = (B - A).head<2>(), w = (C - A).head<2>();
  const double zu = B.z() - A.z(), zw = C.z() - A.z();
  const double ww = w.squaredNorm();

  // The t in [0, 1 - s] closest to the axis, and its squared distance (convex in s).
  auto closest_t = [&](double s) {
    const Vec2 q = q0 + s * u;
    const double top = std::max(0.0, 1.0 - s);
    return ww > 0 ? std::clamp(-q.dot(w) / ww, 0.0, top) : 0.0;
  };
  auto closest_d2 = [&](double s) { return (q0 + s * u + closest_t(s) * w).squaredNorm(); };
  auto feasible = [&](double s) { return closest_d2(s) <= R2; };

  const auto [d2_min, s_near] = golden_min(closest_d2, 0.0, 1.0);
  if (d2_min > R2) return kNothing;
  const double s_lo = feasible_end(feasible, s_near, 0.0);
  const double s_hi = feasible_end(feasible, s_near, 1.0);

  // Best tip over the slice at s: t between the roots of |q + t w|^2 = R^2, within [0, 1 - s].
  auto slice_max = [&](double s) {
    const Vec2 q = q0 + s * u;
    const double top = std::max(0.0, 1.0 - s);
    double lo = 0.0, hi = top;
    if (ww > 0) {
      const double qw = q.dot(w), qq = q.squaredNorm() - R2;
      const double root = std::sqrt(std::max(0.0, qw * qw - ww * qq));
      const double k = -(qw + (qw >= 0 ? root : -root));  // the stable pair of roots k / ww and qq / k
      double r1 = k / ww, r2 = k != 0 ? qq / k : r1;
      if (r1 > r2) std::swap(r1, r2);
      lo = std::max(lo, r1), hi = std::min(hi, r2);
      if (lo > hi) lo = hi = closest_t(s);  // rounding at the end of the feasible interval
    }
    const double z0 = A.z() + s * zu;
    return golden_max([&](double t) { return z0 + t * zw - pr.height((q + t * w).norm()); }, lo, hi);
  };
  return golden_max(slice_max, s_lo, s_hi);
}

double reference_drop(const Cutter& cutter, const Mesh& mesh, double x, double y) {
  const Profile pr(cutter);
  std::vector<std::pair<double, size_t>> candidates;  // (upper bound, face)
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const Vec3 &a = mesh.corner(f, 0), &b = mesh.corner(f, 1), &c = mesh.corner(f, 2);
    const double d = bbox_distance(a, b, c, x, y);
    if (d > pr.R) continue;
    candidates.emplace_back(std::max({a.z(), b.z(), c.z()}) - pr.height(d), f);
  }
  std::sort(candidates.begin(), candidates.end(), [](const auto& p, const auto& q) { return p.first > q.first; });
  double best = kNothing;
  for (const auto& [bound, f] : candidates) {
    if (bound <= best) break;
    best = std::max(best, reference_triangle_drop(cutter, x, y, mesh.corner(f, 0), mesh.corner(f, 1),
                                                  mesh.corner(f, 2)));
  }
  return best;
}

namespace {

// Branch and bound over one triangle: does some point p of it have p.z - h(d) > limit? A piece of the triangle
// (in the parameters s, t) is dropped when an upper bound of p.z - h(d) over it is <= limit: its highest corner
// less h at its box's distance, or, from each corner v inside the footprint, the plane through f(v) with f's
// supergradient there (f = p.z - h(d) is concave, so that plane lies above f), at the piece's highest corner.
// The plane's gap shrinks with the square of the piece's size, so pieces near a contact resolve in a few splits.
bool triangle_exceeds(const Profile& pr, double x, double y, const Vec3& A, const Vec3& B, const Vec3& C,
                      double limit) {
  struct Piece {
    Vec3 p[3];
    int level;
  };
  Piece stack[4 * 40 + 4];
  int top = 0;
  stack[top++] = {{A, B, C}, 0};
  while (top > 0) {
    const Piece piece = stack[--top];
    const Vec3* p = piece.p;
    const double d_box = bbox_distance(p[0], p[1], p[2], x, y);
    if (d_box > pr.R) continue;
    double bound = std::max({p[0].z(), p[1].z(), p[2].z()}) - pr.height(d_box);
    if (bound <= limit) continue;
    for (int i = 0; i < 3; ++i) {
      const Vec2 off(p[i].x() - x, p[i].y() - y);
      const double d = off.norm();
      if (d >= pr.R) continue;
      const double f = p[i].z() - pr.height(d);
      if (f > limit) return true;
      const Vec2 g = d > 0 ? Vec2(-pr.slope(d) / d * off) : Vec2::Zero();  // gradient of -h(d) in x, y
      double plane = -std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) plane = std::max(plane, f + (p[k].z() - p[i].z()) + g.dot((p[k] - p[i]).head<2>()));
      bound = std::min(bound, plane);
    }
    if (bound <= limit) continue;
    if (piece.level >= 40) {
      // Pieces of 1e-12 of the triangle: what is left is rounding, below any tolerance a test uses.
      if (bound > limit + 1e-9) return true;
      continue;
    }
    const Vec3 m01 = 0.5 * (p[0] + p[1]), m12 = 0.5 * (p[1] + p[2]), m20 = 0.5 * (p[2] + p[0]);
    const int l = piece.level + 1;
    stack[top++] = {{p[0], m01, m20}, l};
    stack[top++] = {{m01, p[1], m12}, l};
    stack[top++] = {{m20, m12, p[2]}, l};
    stack[top++] = {{m01, m12, m20}, l};
  }
  return false;
}

}  // namespace

bool reference_gouges(const Cutter& cutter, const Mesh& mesh, const Vec3& tip, double depth) {
  // The cutter eroded by `depth`: radii smaller by it, tip higher by it (a corner smaller than `depth` erodes to a
  // sharp one). A point deeper than `depth` inside the cutter is a point inside the eroded one.
  const Profile full(cutter);
  Cutter eroded = cutter;
  eroded.diameter = cutter.diameter - 2 * depth;
  eroded.corner_radius = std::max(0.0, full.r - depth);
  eroded.type = eroded.corner_radius == 0 ? CutterType::FlatEnd : CutterType::BullNose;
  if (!(eroded.diameter > 0)) return false;
  const Profile pr(eroded);
  const double limit = tip.z() + depth;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const Vec3 &a = mesh.corner(f, 0), &b = mesh.corner(f, 1), &c = mesh.corner(f, 2);
    const double d = bbox_distance(a, b, c, tip.x(), tip.y());
    if (d > pr.R || std::max({a.z(), b.z(), c.z()}) - pr.height(d) <= limit) continue;
    if (triangle_exceeds(pr, tip.x(), tip.y(), a, b, c, limit)) return true;
  }
  return false;
}

ReferenceCheck check_drop(const Cutter& cutter, const Mesh& mesh, double x, double y, double z, double floor,
                          double tolerance) {
  auto ref = [&](double grow) {
    Cutter c = cutter;
    c.diameter *= 1.0 + grow;
    if (c.type == CutterType::BullNose) c.corner_radius = std::min(c.corner_radius, 0.5 * c.diameter);
    return std::max(reference_drop(c, mesh, x, y), floor);
  };
  if (std::abs(ref(0.0) - z) <= tolerance) return ReferenceCheck::Equal;
  // The drop never falls when the cutter grows (its lower surface only flattens and widens).
  if (ref(-1e-9) - tolerance <= z && z <= ref(1e-9) + tolerance) return ReferenceCheck::RimTie;
  return ReferenceCheck::Differs;
}

}  // namespace rosmill::core
