#include "rosmill/gcode/arc_fit.hpp"

#include <cmath>

namespace rosmill::core::gcode {
namespace {

constexpr double kTwoPi = 6.283185307179586;
// Points closer than this in Z lie in the same XY plane (they were written as one height by the planner).
constexpr double kPlaneEpsilon = 1e-7;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Centre of the circle through three points; false when they are (nearly) collinear.
bool circumcentre(const Vec2& a, const Vec2& b, const Vec2& c, Vec2& centre) {
  const Vec2 ab = b - a, ac = c - a;
  const double d = 2.0 * cross(ab, ac);
  const double scale = ab.squaredNorm() * ac.squaredNorm();
  if (std::abs(d) <= 1e-12 * std::sqrt(scale) || d == 0.0) return false;
  const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm();
  centre = a + Vec2(ac.y() * ab2 - ab.y() * ac2, ab.x() * ac2 - ac.x() * ab2) / d;
  return true;
}

Vec2 xy(const Vec3& p) { return p.head<2>(); }

// Does the run points[i..j] lie on one arc within the tolerance? Fills `piece` when it does.
bool fits(const std::vector<Vec3>& pts, int i, int j, const ArcFitOptions& o, ArcPiece& piece) {
  const int m = (i + j) / 2;
  Vec2 c;
  if (!circumcentre(xy(pts[i]), xy(pts[m]), xy(pts[j]), c)) return false;
  const double r = (xy(pts[i]) - c).norm();
  if (r < o.min_radius || r > o.max_radius) return false;
  const bool ccw = cross(xy(pts[m]) - xy(pts[i]), xy(pts[j]) - xy(pts[m])) > 0;
  const double z = pts[i].z();
  double sweep = 0.0;
  double prev_dev = 0.0;
  for (int k = i; k <= j; ++k) {
    if (std::abs(pts[k].z() - z) > kPlaneEpsilon) return false;
    const Vec2 rel = xy(pts[k]) - c;
    const double dev = std::abs(rel.norm() - r);
    if (dev > o.tolerance) return false;
    if (k > i) {
      const Vec2 prev = xy(pts[k - 1]) - c;
      const double step = std::atan2(cross(prev, rel), prev.dot(rel));
      if (step == 0.0 || (step > 0) != ccw) return false;  // the run must turn one way around the centre
      sweep += std::abs(step);
      // The chord dips inside the circle by its sagitta; add the worse end's radial deviation.
      const double half = 0.5 * (xy(pts[k]) - xy(pts[k - 1])).norm();
      const double sagitta = r - std::sqrt(std::max(0.0, r * r - half * half));
      if (sagitta + std::max(dev, prev_dev) > o.tolerance) return false;
    }
    prev_dev = dev;
  }
  if (sweep >= kTwoPi - 0.05) return false;  // a full turn is ambiguous for a centre-format arc
  piece = ArcPiece{i, j, true, !ccw, c, r};
  return true;
}

}  // namespace

std::vector<ArcPiece> fit_arcs(const std::vector<Vec3>& pts, const ArcFitOptions& o) {
  std::vector<ArcPiece> pieces;
  const int n = static_cast<int>(pts.size());
  auto add_line = [&](int i) {
    if (!pieces.empty() && !pieces.back().arc && pieces.back().last == i) {
      pieces.back().last = i + 1;
    } else {
      ArcPiece p;
      p.first = i;
      p.last = i + 1;
      pieces.push_back(p);
    }
  };
  int i = 0;
  while (i < n - 1) {
    ArcPiece best, trial;
    bool found = false;
    // Greedy: grow the arc one vertex at a time while it still fits.
    for (int j = i + o.min_segments; j < n && j - i <= o.max_segments; ++j) {
      if (!fits(pts, i, j, o, trial)) break;
      best = trial;
      found = true;
    }
    if (found) {
      pieces.push_back(best);
      i = best.last;
    } else {
      add_line(i);
      ++i;
    }
  }
  return pieces;
}

double distance_to_arc(const Vec2& p, const Vec2& from, const Vec2& to, const Vec2& centre, bool clockwise) {
  const double r = (from - centre).norm();
  const Vec2 a = from - centre, b = to - centre, q = p - centre;
  // Angles measured from `from` in the arc's direction, in [0, 2pi).
  auto along = [&](const Vec2& v) {
    double ang = std::atan2(cross(a, v), a.dot(v));
    if (clockwise) ang = -ang;
    if (ang < 0) ang += kTwoPi;
    return ang;
  };
  if (along(q) <= along(b) + 1e-12) return std::abs(q.norm() - r);
  return std::min((p - from).norm(), (p - to).norm());
}

}  // namespace rosmill::core::gcode
