// Geometry of one swept move on the rows of the grid: a line or an XY arc in its own frame, the x-interval of a
// row inside its footprint, and where along a line the cutter's bottom is lowest over a cell (its "lead").
// Private to the material removal simulation; everything here is inline because it runs once per row.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "rosmill/cutter/contact.hpp"
#include "rosmill/toolpath/canon_arc.hpp"
#include "rosmill/stock/program.hpp"

namespace rosmill::core::stock::sweep {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kVerticalLength = 1e-9;  // mm: a line shorter than this in XY is a vertical move

inline double clamp01(double t) { return std::min(std::max(t, 0.0), 1.0); }
inline double sqrt0(double v) { return std::sqrt(std::max(v, 0.0)); }

// A line in its own frame: a runs along its XY direction from the start, b across it (b = ey ux - ex uy).
struct LineFrame {
  double ax = 0, ay = 0, az = 0;  // start (the lower end of a vertical move)
  double ux = 1, uy = 0;          // unit XY direction ((1, 0) for a vertical move)
  double inv_ux = 1, inv_uy = kInf;  // their inverses (infinite for 0)
  double L = 0, invL = 0;         // XY length and its inverse (0 for a vertical move)
  double uz = 0;                  // z change (0 for a vertical move: it cuts as its lower end)
  double kz = 0;                  // uz / 3-D length
  int vertical = 0;               // +1 a vertical move down, -1 up (or standing still), 0 a line with XY length

  double a(double x, double y) const { return (x - ax) * ux + (y - ay) * uy; }
  double b(double x, double y) const { return (y - ay) * ux - (x - ax) * uy; }
};

inline LineFrame line_frame(const Vec3& from, const Vec3& to) {
  LineFrame f;
  const double dx = to.x() - from.x(), dy = to.y() - from.y(), dz = to.z() - from.z();
  const double L = std::sqrt(dx * dx + dy * dy);
  f.ax = from.x();
  f.ay = from.y();
  if (L < kVerticalLength) {
    f.az = std::min(from.z(), to.z());
    f.vertical = dz < 0 ? 1 : -1;
    return f;
  }
  f.az = from.z();
  f.ux = dx / L;
  f.uy = dy / L;
  f.inv_ux = f.ux != 0 ? 1 / f.ux : kInf;
  f.inv_uy = f.uy != 0 ? 1 / f.uy : kInf;
  f.L = L;
  f.invL = 1 / L;
  f.uz = dz;
  f.kz = dz / std::sqrt(L * L + dz * dz);
  return f;
}

// x-interval where the row at height y meets the disc of squared radius R2 around (px, py) (grows [lo, hi]).
inline void disc_row(double px, double py, double R2, double y, double& lo, double& hi) {
  const double dy = y - py, w2 = R2 - dy * dy;
  if (w2 < 0) return;
  const double w = std::sqrt(w2);
  lo = std::min(lo, px - w);
  hi = std::max(hi, px + w);
}

// Narrows [lo, hi] to the v with c·v in [L, H].
inline void clip_linear(double c, double L, double H, double& lo, double& hi) {
  if (c > 0) { lo = std::max(lo, L / c); hi = std::min(hi, H / c); }
  else if (c < 0) { lo = std::max(lo, H / c); hi = std::min(hi, L / c); }
  else if (L > 0 || H < 0) { lo = kInf; hi = -kInf; }
}

// Narrows [lo, hi] to the x with v0 + c x in [L, H], given 1 / c (infinite for c = 0: v0 decides alone).
inline void clip_slope(double v0, double c, double inv_c, double L, double H, double& lo, double& hi) {
  if (c == 0) {
    if (!(v0 >= L && v0 <= H)) { lo = kInf; hi = -kInf; }
    return;
  }
  const double p = (L - v0) * inv_c, q = (H - v0) * inv_c;
  lo = std::max(lo, std::min(p, q));
  hi = std::min(hi, std::max(p, q));
}

// Narrows [lo, hi] (x on the row at height y) to where a is in [amin, amax].
inline void clip_along(const LineFrame& f, double y, double amin, double amax, double& lo, double& hi) {
  clip_slope((y - f.ay) * f.uy - f.ax * f.ux, f.ux, f.inv_ux, amin, amax, lo, hi);
}

// Narrows [lo, hi] (x on the row at height y) to where |b| <= R.
inline void clip_across(const LineFrame& f, double y, double R, double& lo, double& hi) {
  clip_slope((y - f.ay) * f.ux + f.ax * f.uy, -f.uy, -f.inv_uy, -R, R, lo, hi);
}

// x-interval of the row at height y inside the capsule of radius R around the line (the two end discs and the
// strip between them: a convex set, so one interval).
inline bool capsule_row(const LineFrame& f, double R, double y, double& lo, double& hi) {
  lo = kInf; hi = -kInf;
  const double R2 = R * R, dy = y - f.ay;
  disc_row(f.ax, f.ay, R2, y, lo, hi);
  if (f.L > 0) {
    disc_row(f.ax + f.L * f.ux, f.ay + f.L * f.uy, R2, y, lo, hi);
    double slo = -kInf, shi = kInf;  // x - ax in the strip: 0 <= a <= L and |b| <= R
    clip_linear(f.ux, -dy * f.uy, f.L - dy * f.uy, slo, shi);
    clip_linear(-f.uy, -R - f.ux * dy, R - f.ux * dy, slo, shi);
    if (slo <= shi) { lo = std::min(lo, f.ax + slo); hi = std::max(hi, f.ax + shi); }
  }
  return lo <= hi;
}

// Where along a line its bottom is lowest over a cell (a, b): at a - g, with g = a - kappa W(b) and
// W(b) = sqrt(max(0, rho^2 - b^2)); the move's parameter there is g / L. Written out for:
//   ball:       kappa = uz / 3-D length, rho = R  (the clamped stationary point of its convex bottom)
//   flat end:   kappa = +1 going up or level, -1 going down, rho = R  (where the disc enters or leaves the cell)
//   bull, level: kappa = 1, rho = R - r  (entering its flat disc, else the nearest point)
//   the axis itself (the finishing trace): kappa = 0 (the nearest point)
// A vertical move's bottom is lowest at its lower end: g = +inf going down, -inf going up.
struct Lead {
  double kappa = 0, rho = 0;
};

// Narrows [lo, hi] (x on the row at height y) to a superset of where g is in [gmin, gmax]: W is bounded over
// the b the interval spans (W is concave in b), which bounds a; again while the interval is wider than `refine`,
// since a narrower interval spans less b.
inline void clip_lead(const LineFrame& f, const Lead& d, double y, double gmin, double gmax, double& lo, double& hi,
                      double refine = 0) {
  if (lo > hi) return;
  if (f.vertical) {
    const double g = f.vertical > 0 ? kInf : -kInf;
    if (!(g >= gmin && g <= gmax)) { lo = kInf; hi = -kInf; }
    return;
  }
  if (d.kappa == 0) { clip_along(f, y, gmin, gmax, lo, hi); return; }
  for (int pass = 0; pass < 2 && lo <= hi && (pass == 0 || hi - lo > refine); ++pass) {
    const double b0 = f.b(lo, y), b1 = f.b(hi, y);
    const double near = (b0 <= 0) == (b1 >= 0) ? 0.0 : std::min(std::abs(b0), std::abs(b1));
    const double far = std::max(std::abs(b0), std::abs(b1));
    const double w_lo = sqrt0(d.rho * d.rho - far * far), w_hi = sqrt0(d.rho * d.rho - near * near);
    const double k_lo = d.kappa > 0 ? d.kappa * w_lo : d.kappa * w_hi;
    const double k_hi = d.kappa > 0 ? d.kappa * w_hi : d.kappa * w_lo;
    clip_along(f, y, gmin + k_lo, gmax + k_hi, lo, hi);
  }
}

// A level XY arc: inside its sweep the distance to the path is |rho - |e||, outside it the nearer end's.
struct ArcFrame {
  double cx, cy, rho, z;
  double s0x, s0y, s1x, s1y;  // the arc counter-clockwise from s0 to s1 (vectors from the centre)
  bool full, small;           // a full turn; a sweep of at most half a turn
  double xmin, xmax;          // the path's x extent
};

inline ArcFrame arc_frame(const CanonMove& m) {
  ArcFrame a{};
  a.cx = m.centre.x();
  a.cy = m.centre.y();
  a.z = m.from.z();
  const Vec2 p = m.from.head<2>() - m.centre, q = m.to.head<2>() - m.centre;
  a.rho = p.norm();
  const bool ccw = m.shape == MoveShape::ArcCCW;
  const Vec2& s0 = ccw ? p : q;
  const Vec2& s1 = ccw ? q : p;
  a.s0x = s0.x(); a.s0y = s0.y(); a.s1x = s1.x(); a.s1y = s1.y();
  const double sweep = std::abs(arc_sweep(m));
  a.full = sweep >= 2 * M_PI - 1e-12;
  a.small = sweep <= M_PI;
  Vec2 lo, hi;
  move_xy_bounds(m, lo, hi);
  a.xmin = lo.x();
  a.xmax = hi.x();
  return a;
}

// A superset of the row's cells within R of the arc: the disc of radius rho + R around the centre, cut to the
// path's x extent grown by R.
inline bool arc_row(const ArcFrame& a, double R, double y, double& lo, double& hi) {
  lo = kInf; hi = -kInf;
  disc_row(a.cx, a.cy, (a.rho + R) * (a.rho + R), y, lo, hi);
  lo = std::max(lo, a.xmin - R);
  hi = std::min(hi, a.xmax + R);
  return lo <= hi;
}

}  // namespace rosmill::core::stock::sweep
