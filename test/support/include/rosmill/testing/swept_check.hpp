// An independent check of what a job's moves cut, for the tests of multi-setup jobs: whether a point of the
// workpiece lies in the volume some move's cutter swept, with every setup's moves mapped back through its frame. The
// moves come from the job's toolpaths, or from its written programs as LinuxCNC's interpreter reads them
// (program_sweep.hpp).
// It shares no code with the stock model or the verifier (no grid, no height field, no removal kernel): a cutter
// with its tip at c holds the points x within its radius of its axis and at or above c.z + h(d), d the distance from
// the axis and h the profile's height there (a flat bottom, then the corner's quarter circle); everything above is
// tool too. Along a straight move that height over a fixed point, g(t) = c.z(t) + h(d(t)), is convex in t (h is
// convex and rising, d convex), so its least value over the part of the move within reach is found by a golden-
// section search to a micrometre of travel.
#pragma once
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <cstdint>
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

inline double corner_radius_of(const Cutter& c) {
  return c.type == CutterType::FlatEnd ? 0 : c.type == CutterType::BallEnd ? c.radius() : c.corner_radius;
}

// A move of a cutter from tip a to tip b, with its box of reach.
inline Segment segment(const Vec3& a, const Vec3& b, double radius, double corner) {
  Segment s{a, b, radius, corner, a.cwiseMin(b), a.cwiseMax(b)};
  s.lo.head<2>() -= Vec2::Constant(radius);
  s.hi.head<2>() += Vec2::Constant(radius);
  s.hi.z() = INFINITY;  // the tool above the tip
  return s;
}

// The moves of every operation of every setup, as segments in the workpiece frame's setup turn: one list per setup,
// with a grid of bins over its XY (kBin mm) listing the segments whose reach meets each, made on the first query.
struct SweptJob {
  static constexpr double kBin = 2.0;
  static constexpr double kNearest = 0.5;  // the bins hold what comes this near them: the most a slack may ask for
  std::vector<SetupFrame> frames;
  std::vector<std::vector<Segment>> segments;  // per frame, in that frame

  size_t frame_of(const SetupFrame& frame) {
    size_t f = 0;
    while (f < frames.size() && !frames[f].same_as(frame)) ++f;
    if (f == frames.size()) {
      frames.push_back(frame);
      segments.emplace_back();
    }
    bins_.clear();
    return f;
  }

  void add(const SetupFrame& frame, const Job& job) {
    const size_t f = frame_of(frame);
    for (const auto& tp : job) {
      const Cutter& c = tp.tool.cutter;
      Vec3 at = tp.start;
      for (const auto& pass : tp.passes)
        for (const auto& m : pass.moves) {
          segments[f].push_back(segment(at, m.to, c.radius(), corner_radius_of(c)));
          at = m.to;
        }
    }
  }

  void add_segments(const SetupFrame& frame, const std::vector<Segment>& more) {
    const size_t f = frame_of(frame);
    segments[f].insert(segments[f].end(), more.begin(), more.end());
  }

  // Whether the point (workpiece frame) lies in the tool at some position of some move, within `slack` mm (a point
  // that deep inside counts; slack < 0 asks for points the tool came that near). Not thread-safe on its first call.
  bool swept(const Vec3& point, double slack = 0.0) const {
    if (slack < -kNearest) throw std::invalid_argument("swept_check: a slack below -0.5 mm");
    if (bins_.size() != frames.size()) index();
    for (size_t f = 0; f < frames.size(); ++f) {
      const Vec3 q = frames[f].to_setup_frame(point);
      const Bins& b = bins_[f];
      const int i = static_cast<int>(std::floor((q.x() - b.x0) / kBin));
      const int j = static_cast<int>(std::floor((q.y() - b.y0) / kBin));
      if (i < 0 || j < 0 || i >= b.nx || j >= b.ny) continue;
      const Vec3 grow = Vec3::Constant(std::max(0.0, -slack));  // a point the tool came near may lie beyond its box
      for (const uint32_t k : b.cells[static_cast<size_t>(j) * b.nx + i]) {
        const Segment& s = segments[f][k];
        if ((q.array() >= (s.lo - grow).array()).all() && (q.array() <= (s.hi + grow).array()).all() &&
            in_segment(s, q, slack))
          return true;
      }
    }
    return false;
  }

 private:
  struct Bins {
    double x0 = 0, y0 = 0;
    int nx = 0, ny = 0;
    std::vector<std::vector<uint32_t>> cells;
  };
  mutable std::vector<Bins> bins_;

  void index() const {
    bins_.assign(frames.size(), {});
    for (size_t f = 0; f < frames.size(); ++f) {
      Bins& b = bins_[f];
      double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
      for (const Segment& s : segments[f]) {
        x0 = std::min(x0, s.lo.x()), y0 = std::min(y0, s.lo.y());
        x1 = std::max(x1, s.hi.x()), y1 = std::max(y1, s.hi.y());
      }
      if (!(x0 <= x1)) continue;
      b.x0 = x0, b.y0 = y0;
      b.nx = static_cast<int>((x1 - x0) / kBin) + 1, b.ny = static_cast<int>((y1 - y0) / kBin) + 1;
      b.cells.assign(static_cast<size_t>(b.nx) * b.ny, {});
      for (uint32_t k = 0; k < segments[f].size(); ++k) {
        const Segment& s = segments[f][k];
        const int i0 = std::max(0, static_cast<int>((s.lo.x() - kNearest - x0) / kBin));
        const int i1 = std::min(b.nx - 1, static_cast<int>((s.hi.x() + kNearest - x0) / kBin));
        const int j0 = std::max(0, static_cast<int>((s.lo.y() - kNearest - y0) / kBin));
        const int j1 = std::min(b.ny - 1, static_cast<int>((s.hi.y() + kNearest - y0) / kBin));
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i) b.cells[static_cast<size_t>(j) * b.nx + i].push_back(k);
      }
    }
  }

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
