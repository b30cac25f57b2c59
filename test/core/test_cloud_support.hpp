// Test helpers for the cloud suites: clouds sampled from meshes with a known covering radius, noise, the
// sampling bound against the mesh drop-cutter, and brute-force checks of cutters against points.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rosmill/cloud/cloud_surface.hpp"
#include "rosmill/cutter/contact.hpp"
#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/toolpath/toolpath.hpp"

namespace cloudtest {

using rosmill::core::Cutter;
using rosmill::core::Vec2;
using rosmill::core::Vec3;

struct Sampling {
  std::vector<Vec3> pts;
  double covering = 0;  // every point of the mesh is within this distance (3-D) of a sample
};

// Uniform sampling with a covering radius that is proven, not measured: every triangle is cut into n² copies of
// itself scaled by 1/n (the barycentric lattice i/n, j/n; n = ceil(longest edge / s)) and the lattice nodes
// are the samples. A point of the triangle lies in a lattice triangle whose edges are at most s, so it is
// within s/sqrt(3) of one of its corners: an acute triangle's farthest point from its corners is the
// circumcentre, at a/(2 sin A) <= a/sqrt(3) (a the longest side, its angle A between 60 and 90 degrees); a right
// or obtuse triangle's farthest point lies on the longest side, at most a/2 from a corner.
inline Sampling sample_mesh(const rosmill::core::Mesh& m, double s) {
  Sampling out;
  out.covering = s / std::sqrt(3.0);
  for (size_t f = 0; f < m.face_count(); ++f) {
    const Vec3 a = m.corner(f, 0), b = m.corner(f, 1), c = m.corner(f, 2);
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int n = std::max(1, int(std::ceil(longest / s)));
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) out.pts.push_back(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n));
  }
  return out;
}

// Adds N(0, sigma) to every coordinate; returns the largest displacement applied (3-D).
inline double add_noise(std::vector<Vec3>& pts, double sigma, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, sigma);
  double worst = 0;
  for (Vec3& p : pts) {
    const Vec3 n(g(rng), g(rng), g(rng));
    p += n;
    worst = std::max(worst, n.norm());
  }
  return worst;
}

// The cutter eroded by r (every point at least r inside it), tip raised by r: a ball or flat end mill of radius
// R - r. Used only for ball and flat cutters.
inline Cutter eroded(const Cutter& c, double r) {
  return c.type == rosmill::core::CutterType::BallEnd ? Cutter::ball(c.diameter - 2 * r)
                                                      : Cutter::flat(c.diameter - 2 * r);
}

// The sampling bound of a cloud's drop against the mesh it was sampled from. The points lie within `eta` of the
// mesh and every mesh point lies within r = rho + eta of a point (rho: the sampling's covering radius, eta: the
// largest noise displacement). Then, for the cloud's drop z of cutter C (the points see C grown by its support
// disc: S = surface.supported(C)):
//   z >= mesh drop of C eroded by r, less r: at height z and above, C holds no point, so the eroded cutter
//        (r inside C) holds no mesh point, or some point would be within r of it, inside C;
//   z <= mesh drop of S grown by eta (offset_cutter), plus eta: S touches a point p at z, so S grown by eta,
//        eta lower, holds the mesh point within eta of p.
struct Bound {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  bool misses = false;  // the grown cutter misses the mesh: the cloud's cutter touches nothing
};
inline Bound sampling_bound(const rosmill::core::MeshSurface& mesh, const rosmill::core::CloudSurface& cloud,
                            const Cutter& c, double rho, double eta, double x, double y) {
  Bound b;
  const double r = rho + eta;
  const rosmill::core::Drop lo = mesh.drop(eroded(c, r), x, y);
  if (lo.touched) b.lo = lo.z - r;
  const rosmill::core::Drop hi = mesh.drop(rosmill::core::offset_cutter(cloud.supported(c), eta), x, y);
  if (hi.touched) b.hi = hi.z + eta;
  b.misses = !hi.touched;
  return b;
}

// On level ground the bound is much tighter: where C and a flat end mill of C's reach grown by eta land at the
// same height z0 on the mesh, the mesh's highest point within that reach is under the axis at z0 (C can only
// touch there at its tip) and, lying on a level facet, a level edge or a corner, it has a sample at z0 within
// rho in plan view. With noise the cloud's drop is then within [z0 - eta - h_S(rho + eta), z0 + eta] (h_S: the
// height of S's underside at that distance). Ball cutters only; returns false where the ground is not level.
inline bool level_ground(const rosmill::core::MeshSurface& mesh, const rosmill::core::CloudSurface& cloud,
                         const Cutter& c, double rho, double eta, double x, double y, Bound& b) {
  const Cutter s = cloud.supported(c);
  const rosmill::core::CutterProfile sp(s);
  if (c.type != rosmill::core::CutterType::BallEnd || rho + eta > sp.R) return false;
  const rosmill::core::Drop d = mesh.drop(c, x, y), f = mesh.drop(Cutter::flat(s.diameter + 2 * eta), x, y);
  if (!d.touched || !f.touched || std::abs(d.z - f.z) > 1e-9) return false;
  b.lo = d.z - eta - sp.height(std::min(rho + eta, sp.R));
  b.hi = d.z + eta;
  return true;
}

// Points sorted by x, for brute-force checks: every point within the cutter's x-range is looked at (no grid, no
// pruning by height); points outside it cannot be under the cutter.
class SortedPoints {
 public:
  explicit SortedPoints(std::vector<Vec3> pts) : pts_(std::move(pts)) {
    std::sort(pts_.begin(), pts_.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
  }
  const std::vector<Vec3>& points() const { return pts_; }

  // How far the cutter with its tip at `tip` goes into the points: the largest z_p - (height of the cutter's
  // underside above p) over the points under its footprint; <= 0: clear. -inf when none is under it.
  double penetration(const Cutter& c, const Vec3& tip) const {
    const rosmill::core::CutterProfile cp(c);
    auto lo =
        std::lower_bound(pts_.begin(), pts_.end(), tip.x() - cp.R, [](const Vec3& p, double x) { return p.x() < x; });
    double worst = -std::numeric_limits<double>::infinity();
    for (auto p = lo; p != pts_.end() && p->x() <= tip.x() + cp.R; ++p) {
      const double d2 = (p->head<2>() - tip.head<2>()).squaredNorm();
      if (d2 <= cp.R2) worst = std::max(worst, p->z() - (tip.z() + cp.height_sq(d2)));
    }
    return worst;
  }

 private:
  std::vector<Vec3> pts_;
};

// Cutting positions of a toolpath: every feed or plunge move's end (the cutter locations) or, with per_move > 1,
// also per_move - 1 points inside each such move.
inline std::vector<Vec3> cut_positions(const rosmill::core::Toolpath& tp, int per_move) {
  std::vector<Vec3> out;
  Vec3 at = tp.start;
  for (const auto& pass : tp.passes)
    for (const auto& m : pass.moves) {
      if (m.type != rosmill::core::MoveType::Rapid)
        for (int i = 1; i <= per_move; ++i) out.push_back(at + (m.to - at) * (double(i) / per_move));
      at = m.to;
    }
  return out;
}

// The cutter locations of a toolpath's feed moves (the ends of its cutting moves, approaches and retracts
// excluded).
inline std::vector<Vec3> feed_locations(const rosmill::core::Toolpath& tp) {
  std::vector<Vec3> out;
  for (const auto& pass : tp.passes)
    for (const auto& m : pass.moves)
      if (m.type == rosmill::core::MoveType::Feed) out.push_back(m.to);
  return out;
}

}  // namespace cloudtest
