// An independent check of what a job's toolpaths cut, for the tests of multi-setup jobs: whether a point of the
// workpiece lies in the volume some move's cutter swept, with every setup's moves mapped back through its frame.
// It shares no code with the stock model or the verifier (no grid, no height field, no removal kernel): a cutter
// with its tip at c holds the points x within its radius of its axis and at or above c.z + h(d), d the distance from
// the axis and h the profile's height there (a flat bottom, then the corner's quarter circle); everything above is
// tool too. Along a straight move that height over a fixed point, g(t) = c.z(t) + h(d(t)), is convex in t (h is
// convex and rising, d convex), so its least value over the part of the move within reach is found by a golden-
// section search to a micrometre of travel.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/toolpath/job.hpp"

namespace swept_check {

using rosmill::core::Cutter;
using rosmill::core::CutterType;
using rosmill::core::Job;
using rosmill::core::SetupFrame;
using rosmill::core::Vec2;
using rosmill::core::Vec3;

struct Segment {
  Vec3 a, b;
  double radius, corner;  // the cutter's
  Vec3 lo, hi;            // the swept box (the tool's reach around the segment), for culling
};

// The height of the cutter's surface above its tip at distance d from its axis (d <= radius).
inline double profile(const Segment& s, double d) {
  const double flat = s.radius - s.corner;
  if (d <= flat) return 0.0;
  const double e = std::min(d - flat, s.corner);
  return s.corner - std::sqrt(std::max(0.0, s.corner * s.corner - e * e));
}

// The moves of every operation of every setup, as segments in the workpiece frame's setup turn: one list per setup.
struct SweptJob {
  std::vector<SetupFrame> frames;
  std::vector<std::vector<Segment>> segments;  // per frame, in that frame

  void add(const SetupFrame& frame, const Job& job) {
    size_t f = 0;
    while (f < frames.size() && !frames[f].same_as(frame)) ++f;
    if (f == frames.size()) {
      frames.push_back(frame);
      segments.emplace_back();
    }
    for (const auto& tp : job) {
      const Cutter& c = tp.tool.cutter;
      const double corner = c.type == CutterType::FlatEnd ? 0 : c.type == CutterType::BallEnd ? c.radius() : c.corner_radius;
      Vec3 at = tp.start;
      for (const auto& pass : tp.passes)
        for (const auto& m : pass.moves) {
          Segment s{at, m.to, c.radius(), corner, at.cwiseMin(m.to), at.cwiseMax(m.to)};
          s.lo.head<2>() -= Vec2::Constant(s.radius);
          s.hi.head<2>() += Vec2::Constant(s.radius);
          s.hi.z() = INFINITY;  // the tool above the tip
          segments[f].push_back(s);
          at = m.to;
        }
    }
  }

  // Whether the point (workpiece frame) lies in the tool at some position of some move, within `slack` mm (a point
  // that deep inside counts; slack < 0 asks for points the tool came that near).
  bool swept(const Vec3& point, double slack = 0.0) const {
    for (size_t f = 0; f < frames.size(); ++f) {
      const Vec3 q = frames[f].to_setup_frame(point);
      for (const Segment& s : segments[f])
        if ((q.array() >= s.lo.array()).all() && (q.array() <= s.hi.array()).all() && in_segment(s, q, slack))
          return true;
    }
    return false;
  }

 private:
  static bool in_segment(const Segment& s, const Vec3& q, double slack) {
    // The part of the move where q is within the radius (less the slack) of the axis: d(t)^2 is a quadratic.
    const Vec2 a = s.a.head<2>(), u = s.b.head<2>() - a, w = q.head<2>() - a;
    const double reach = s.radius - slack;
    if (!(reach > 0)) return false;
    const double A = u.squaredNorm(), B = -2 * u.dot(w), C = w.squaredNorm() - reach * reach;
    double t0 = 0, t1 = 1;
    if (A < 1e-18) {
      if (C > 0) return false;
    } else {
      const double disc = B * B - 4 * A * C;
      if (disc < 0) return false;
      const double r = std::sqrt(disc);
      t0 = std::max(0.0, (-B - r) / (2 * A));
      t1 = std::min(1.0, (-B + r) / (2 * A));
      if (t0 > t1) return false;
    }
    const auto g = [&](double t) {
      const Vec3 c = s.a + t * (s.b - s.a);
      return c.z() + profile(s, std::min((q.head<2>() - c.head<2>()).norm(), s.radius));
    };
    // Golden-section search for the least tool height over q on [t0, t1].
    const double phi = (std::sqrt(5.0) - 1) / 2;
    double lo = t0, hi = t1, x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo), g1 = g(x1), g2 = g(x2);
    const double length = (s.b - s.a).norm();
    while ((hi - lo) * length > 1e-4) {
      if (g1 < g2) hi = x2, x2 = x1, g2 = g1, x1 = hi - phi * (hi - lo), g1 = g(x1);
      else lo = x1, x1 = x2, g1 = g2, x2 = lo + phi * (hi - lo), g2 = g(x2);
    }
    const double least = std::min({g(t0), g(t1), g1, g2});
    return q.z() >= least + slack;
  }
};

}  // namespace swept_check
