#include "rosmill/cloud/cloud_sweep.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/cutter/contact.hpp"

namespace rosmill::core {
namespace {

// One move, prepared once: plan start A, unit direction u, plan length L, tip slope m (rise per mm of plan).
struct MoveFrame {
  Vec2 A, u;
  double L, m, k, az;  // k = 1 / sqrt(1 + m²)
  MoveFrame(const Vec3& a, const Vec3& b) : A(a.head<2>()), az(a.z()) {
    const Vec2 ab = (b - a).head<2>();
    L = ab.norm();
    u = L > 0 ? Vec2(ab / L) : Vec2(1, 0);
    m = L > 0 ? (b.z() - a.z()) / L : 0.0;
    k = 1.0 / std::sqrt(1.0 + m * m);
  }
};

// A ball of radius R (the common case, in closed form): along the move the point p, at distance s_p along it
// and e across, is inside the ball by z_p - tip(s) - R + sqrt(ρ² - (s - s_p)²) (ρ² = R² - e²). The maximum over
// s is where the slope of the circle equals the tip's: s* = s_p - m ρ / sqrt(1 + m²). Outside (0, L) the
// maximum is at an end of the move, a cutter location, which no point enters. Returns the depth and s*.
double ball_depth(const MoveFrame& f, double R2, double R, const GridPoint& p, double* s_at) {
  const Vec2 ap(p.x - f.A.x(), p.y - f.A.y());
  const double sp = ap.dot(f.u), rho2 = R2 - (ap.squaredNorm() - sp * sp);
  if (rho2 <= 0) return -INFINITY;
  const double rho = std::sqrt(rho2);
  const double s = sp - f.m * rho * f.k;
  if (!(s > 0 && s < f.L)) return -INFINITY;
  *s_at = s;
  return p.z - f.az - f.m * s - R + rho * f.k;
}

// Any other cutter: in the cutter's frame the point travels the edge from p - a to p - b; the edge contact
// (cutter/contact.hpp) is the deepest it goes inside the move.
double edge_depth(const CutterProfile& cp, const GridPoint& p, const Vec3& a, const Vec3& b) {
  const double P[3] = {p.x - a.x(), p.y - a.y(), p.z - a.z()};
  const double Q[3] = {p.x - b.x(), p.y - b.y(), p.z - b.z()};
  return edge_contact(cp, 0, 0, P, Q);
}

// Where along the move (0..1) the point is deepest, for the edge case: golden-section search of the concave
// depth over the part of the move that has the point under the footprint.
double deepest_at(const CutterProfile& cp, const GridPoint& p, const Vec3& a, const Vec3& b) {
  const Vec2 ab = (b - a).head<2>(), ap(p.x - a.x(), p.y - a.y());
  const double L2 = ab.squaredNorm();
  if (L2 < 1e-24) return a.z() <= b.z() ? 0.0 : 1.0;
  const double t0 = ap.dot(ab) / L2, e2 = std::max(0.0, ap.squaredNorm() - t0 * t0 * L2);
  const double half = std::sqrt(std::max(0.0, cp.R2 - e2) / L2);
  double lo = std::max(0.0, t0 - half), hi = std::min(1.0, t0 + half);
  auto depth = [&](double t) {
    const Vec2 q = ap - ab * t;
    return p.z - (a.z() + (b.z() - a.z()) * t) - cp.height_sq(std::min(q.squaredNorm(), cp.R2));
  };
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 80 && hi - lo > 1e-12; ++it) {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    if (depth(m1) < depth(m2))
      lo = m1;
    else
      hi = m2;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

SweepHit sweep_depth(const CloudSurface& surface, const Cutter& cutter, const Vec3& a, const Vec3& b, double floor) {
  const CutterProfile cp(cutter);
  const bool ball = cp.type == CutterType::BallEnd;
  const MoveFrame f(a, b);
  const CloudGrid& g = surface.grid();
  const double half_diag = g.cell() * M_SQRT1_2;
  SweepHit hit{floor, 0.0};
  const GridPoint* worst = nullptr;
  double worst_s = 0.0;
  const Vec2 B = b.head<2>();
  const double lowest_tip = std::min(a.z(), b.z());
  const int c0 = g.col(std::min(f.A.x(), B.x()) - cp.R), c1 = g.col(std::max(f.A.x(), B.x()) + cp.R);
  const int r0 = g.row(std::min(f.A.y(), B.y()) - cp.R), r1 = g.row(std::max(f.A.y(), B.y()) + cp.R);
  for (int row = r0; row <= r1; ++row)
    for (int col = c0; col <= c1; ++col) {
      const size_t cell = g.index(col, row);
      // No point of the cell above the move's lowest tip by more than the depth found: nothing to look at
      // (empty cells too, zmax -inf).
      if (g.zmax(cell) - lowest_tip <= hit.depth) continue;
      // The cell's centre, its distance from the move's plan segment and the stretch of the move that can have
      // the cell under the footprint: bounds on how deep any of its points can go.
      const Vec2 centre(g.x0() + (col + 0.5) * g.cell(), g.y0() + (row + 0.5) * g.cell());
      const double sc = (centre - f.A).dot(f.u);
      const double dist = (centre - (f.A + f.u * std::clamp(sc, 0.0, f.L))).norm();
      if (dist - half_diag > cp.R) continue;
      const double s_lo = std::clamp(sc - cp.R - half_diag, 0.0, f.L), s_hi = std::clamp(sc + cp.R + half_diag, 0.0, f.L);
      const double tip_min = f.az + f.m * (f.m > 0 ? s_lo : s_hi);
      const double dmin = std::max(0.0, dist - half_diag);
      if (g.zmax(cell) - cp.height_sq(dmin * dmin) - tip_min <= hit.depth) continue;
      for (const GridPoint *p = g.begin(cell), *e = g.end(cell); p != e; ++p) {
        if (p->z - tip_min <= hit.depth) continue;
        double s = 0.0;
        const double d = ball ? ball_depth(f, cp.R2, cp.R, *p, &s) : edge_depth(cp, *p, a, b);
        if (d > hit.depth) hit.depth = d, worst = p, worst_s = s;
      }
    }
  if (!worst) return SweepHit{floor, 0.0};
  hit.at = ball ? (f.L > 0 ? worst_s / f.L : 0.0) : deepest_at(cp, *worst, a, b);
  return hit;
}

}  // namespace rosmill::core
