// Independent gouge checks for the rostests: the cutter is swept along a published msg::Toolpath in small steps and
// compared with the known shape directly (point-triangle distances, cloud points in the cutter), not with the
// planner's own drop-cutter. Millimetres inside; the message is converted with the ROS edge's functions.
#pragma once
#include <algorithm>
#include <string>
#include <vector>

#include "rosmill/ros/namespaces.hpp"
#include "rosmill/Toolpath.h"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/ros/convert.hpp"

namespace rosmill::rostest {
using namespace ::rosmill::core;
namespace msg = ::rosmill;

struct Gouge {
  double depth = 0.0;      // mm the cutter reaches into the shape (0: none)
  Vec3 at = Vec3::Zero();  // tool tip where it is deepest
  size_t samples = 0;      // cutter positions tested
};

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
inline Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Tool tip positions every `step` mm along all moves of the toolpath (rapids included: a rapid through material
// is a defect too), in the toolpath's own (setup) frame.
inline std::vector<Vec3> swept_tips(const msg::Toolpath& tp, double step) {
  std::vector<Vec3> tips;
  Vec3 at = edge::from_point_msg(tp.start);
  tips.push_back(at);
  for (const auto& pass : tp.passes)
    for (const auto& move : pass.moves) {
      const Vec3 to = edge::from_point_msg(move.position);
      const int n = std::max(1, int(std::ceil((to - at).norm() / step)));
      for (int k = 1; k <= n; ++k) tips.push_back(at + (to - at) * (double(k) / n));
      at = to;
    }
  return tips;
}

// Triangles bucketed on an XY grid so that a sample visits only the faces near it.
class FaceGrid {
 public:
  FaceGrid(const Mesh& mesh, double cell) : mesh_(mesh), cell_(cell) {
    box_ = mesh.bbox;
    nx_ = std::max(1, int(std::ceil((box_.max.x() - box_.min.x()) / cell)) + 1);
    ny_ = std::max(1, int(std::ceil((box_.max.y() - box_.min.y()) / cell)) + 1);
    cells_.resize(size_t(nx_) * ny_);
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      const Vec3 &a = mesh.corner(f, 0), &b = mesh.corner(f, 1), &c = mesh.corner(f, 2);
      const Vec3 lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
      for (int i = index(lo.x(), box_.min.x(), nx_); i <= index(hi.x(), box_.min.x(), nx_); ++i)
        for (int j = index(lo.y(), box_.min.y(), ny_); j <= index(hi.y(), box_.min.y(), ny_); ++j)
          cells_[size_t(j) * nx_ + i].push_back(uint32_t(f));
    }
  }
  // Calls f(face) for the faces whose cells meet the square of half-size `reach` around (x, y).
  template <typename F>
  void near(double x, double y, double reach, F&& f) const {
    const int i0 = index(x - reach, box_.min.x(), nx_), i1 = index(x + reach, box_.min.x(), nx_);
    const int j0 = index(y - reach, box_.min.y(), ny_), j1 = index(y + reach, box_.min.y(), ny_);
    if (x + reach < box_.min.x() || x - reach > box_.max.x() || y + reach < box_.min.y() || y - reach > box_.max.y())
      return;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        for (uint32_t face : cells_[size_t(j) * nx_ + i]) f(face);
  }

 private:
  int index(double v, double origin, int n) const { return std::clamp(int((v - origin) / cell_), 0, n - 1); }
  const Mesh& mesh_;
  double cell_;
  Box3 box_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<uint32_t>> cells_;
};

// A ball-end cutter of radius r (tip at the bottom of the ball) against a mesh in the same frame: how far the
// ball reaches inside the surface (r - distance from its centre to the nearest triangle).
inline Gouge ball_gouge(const Mesh& mesh, const msg::Toolpath& tp, double step = 0.25) {
  const double r = edge::to_mm(tp.tool.diameter) / 2;
  const FaceGrid grid(mesh, 2 * r);
  Gouge g;
  for (const Vec3& tip : swept_tips(tp, step)) {
    const Vec3 centre = tip + Vec3(0, 0, r);
    ++g.samples;
    if (centre.z() > mesh.bbox.max.z() + r) continue;
    grid.near(centre.x(), centre.y(), r, [&](uint32_t f) {
      const double depth =
          r - (centre - closest_on_triangle(centre, mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2))).norm();
      if (depth > g.depth) g = {depth, tip, g.samples};
    });
  }
  return g;
}

// A flat-end or ball-end cutter of radius r against cloud points (the surface the scan saw): a point is cut when
// it lies inside the cutter body, i.e. within r of the axis and above the cutter's bottom at that radius.
inline Gouge cloud_gouge(const PointCloud& cloud, const msg::Toolpath& tp, double step = 0.5) {
  const double r = edge::to_mm(tp.tool.diameter) / 2;
  const bool ball = tp.tool.cutter_type == msg::Tool::BALL_END;
  Gouge g;
  for (const Vec3& tip : swept_tips(tp, step)) {
    ++g.samples;
    for (const Vec3& p : cloud.points) {
      const double d2 = (p.head<2>() - tip.head<2>()).squaredNorm();
      if (d2 >= r * r) continue;
      const double bottom = ball ? tip.z() + r - std::sqrt(r * r - d2) : tip.z();
      const double depth = p.z() - bottom;
      if (depth > g.depth) g = {depth, tip, g.samples};
    }
  }
  return g;
}

}  // namespace rosmill::rostest
