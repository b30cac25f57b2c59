// Test helpers for the cloud suites: clouds sampled from meshes, noise, a brute-force reference drop-cutter
// (ball against triangles: facet, edge and vertex contacts) and a brute-force gouge check against points.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/plan/toolpath.hpp"

namespace cloudtest {

using rosmill::Vec2;
using rosmill::Vec3;

// Even sampling: each triangle gets a square grid of pitch `spacing` in its own plane plus its edges sampled at
// `spacing` and its corners, so every point of the mesh is within `spacing` of a sample and the density is the
// same in every direction (as a scanner's, roughly).
inline std::vector<Vec3> sample_mesh(const rosmill::Mesh& m, double spacing) {
  std::vector<Vec3> pts;
  for (size_t f = 0; f < m.face_count(); ++f) {
    const Vec3 c[3] = {m.corner(f, 0), m.corner(f, 1), m.corner(f, 2)};
    for (int e = 0; e < 3; ++e) {
      const Vec3 &a = c[e], &b = c[(e + 1) % 3];
      const int n = std::max(1, int(std::ceil((b - a).norm() / spacing)));
      for (int i = 0; i < n; ++i) pts.push_back(a + (b - a) * (double(i) / n));
    }
    const Vec3 e1 = (c[1] - c[0]).normalized();
    Vec3 nrm = (c[1] - c[0]).cross(c[2] - c[0]);
    if (nrm.norm() < 1e-12) continue;
    const Vec3 e2 = nrm.normalized().cross(e1);
    double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
    Vec2 q[3];
    for (int k = 0; k < 3; ++k) {
      q[k] = Vec2((c[k] - c[0]).dot(e1), (c[k] - c[0]).dot(e2));
      u0 = std::min(u0, q[k].x()); u1 = std::max(u1, q[k].x());
      v0 = std::min(v0, q[k].y()); v1 = std::max(v1, q[k].y());
    }
    auto side = [](const Vec2& p, const Vec2& a, const Vec2& b) { return (b - a).x() * (p - a).y() - (b - a).y() * (p - a).x(); };
    for (double u = u0 + 0.5 * spacing; u < u1; u += spacing)
      for (double v = v0 + 0.5 * spacing; v < v1; v += spacing) {
        const Vec2 p(u, v);
        if (side(p, q[0], q[1]) > 0 && side(p, q[1], q[2]) > 0 && side(p, q[2], q[0]) > 0) pts.push_back(c[0] + e1 * u + e2 * v);
      }
  }
  return pts;
}

// Adds N(0, sigma) to every coordinate; returns the largest displacement applied.
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

// Exact tip height of a ball of radius R with its axis at (x, y) dropped onto the mesh (-inf: misses it).
// Also returns cos of the angle between the contact normal and +Z (1 on flat ground).
inline double mesh_ball_drop(const rosmill::Mesh& m, double R, double x, double y, double* cos_contact = nullptr) {
  const Vec2 q(x, y);
  double best = -std::numeric_limits<double>::infinity();
  Vec3 contact(0, 0, 0);
  auto consider = [&](double centre, const Vec3& at) {
    if (centre > best) {
      best = centre;
      contact = at;
    }
  };
  for (size_t f = 0; f < m.face_count(); ++f) {
    const Vec3 &a = m.corner(f, 0), &b = m.corner(f, 1), &c = m.corner(f, 2);
    const double lo_x = std::min({a.x(), b.x(), c.x()}) - R, hi_x = std::max({a.x(), b.x(), c.x()}) + R;
    const double lo_y = std::min({a.y(), b.y(), c.y()}) - R, hi_y = std::max({a.y(), b.y(), c.y()}) + R;
    if (x < lo_x || x > hi_x || y < lo_y || y > hi_y) continue;
    for (const Vec3* v : {&a, &b, &c}) {
      const double d2 = (v->head<2>() - q).squaredNorm();
      if (d2 <= R * R) consider(v->z() + std::sqrt(R * R - d2), *v);
    }
    for (auto [p0, p1] : {std::pair{&a, &b}, std::pair{&b, &c}, std::pair{&c, &a}}) {
      const Vec2 d = (p1->head<2>() - p0->head<2>());
      const double L = d.norm();
      if (L < 1e-12) continue;
      const Vec2 u = d / L;
      const double s_q = (q - p0->head<2>()).dot(u);
      const double l = std::abs((q - p0->head<2>()).dot(Vec2(-u.y(), u.x())));
      if (l >= R) continue;
      const double rho = std::sqrt(R * R - l * l), slope = (p1->z() - p0->z()) / L, k = std::sqrt(1 + slope * slope);
      const double s_c = s_q + rho * slope / k;
      if (s_c < 0 || s_c > L) continue;
      consider(p0->z() + slope * s_q + rho * k, *p0 + (*p1 - *p0) * (s_c / L));
    }
    Vec3 n = (b - a).cross(c - a);
    if (n.norm() < 1e-15) continue;
    n.normalize();
    if (n.z() < 0) n = -n;
    if (n.z() < 1e-9) continue;
    const Vec2 cp = q - R * n.head<2>();
    // Inside the triangle's plan view?
    auto side = [](const Vec2& p, const Vec3& s, const Vec3& e) {
      return (e.x() - s.x()) * (p.y() - s.y()) - (e.y() - s.y()) * (p.x() - s.x());
    };
    const double s1 = side(cp, a, b), s2 = side(cp, b, c), s3 = side(cp, c, a);
    if (!((s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0))) continue;
    const double z = a.z() - (n.x() * (cp.x() - a.x()) + n.y() * (cp.y() - a.y())) / n.z();
    consider(z + R * n.z(), Vec3(cp.x(), cp.y(), z));
  }
  if (cos_contact) *cos_contact = std::isfinite(best) ? std::clamp((best - contact.z()) / R, 0.0, 1.0) : 1.0;
  return best - R;
}

// How far a cutter with its tip at `tip` goes into the points (brute force over all of them): the largest
// z_p + allowance - (height of the cutter's underside above p) over points under the footprint; <= 0: clear.
inline double penetration(const std::vector<Vec3>& pts, const rosmill::Cutter& c, const Vec3& tip, double allowance) {
  const double R = c.radius();
  const double r = c.type == rosmill::CutterType::FlatEnd ? 0.0
                   : c.type == rosmill::CutterType::BallEnd ? R : c.corner_radius;
  const double Rf = R - r;
  double worst = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : pts) {
    const double d = (p.head<2>() - tip.head<2>()).norm();
    if (d > R) continue;
    const double under = d <= Rf ? tip.z() : tip.z() + r - std::sqrt(std::max(0.0, r * r - (d - Rf) * (d - Rf)));
    worst = std::max(worst, p.z() + allowance - under);
  }
  return worst;
}

// Cutting positions of a toolpath sampled along its feed and plunge moves: every vertex and `per_move`
// points inside each move, every `stride`-th move.
inline std::vector<Vec3> feed_samples(const rosmill::Toolpath& tp, size_t stride, int per_move) {
  std::vector<Vec3> out;
  Vec3 at = tp.start;
  size_t k = 0;
  for (const auto& pass : tp.passes)
    for (const auto& m : pass.moves) {
      if (m.type != rosmill::MoveType::Rapid && (k++ % stride) == 0)
        for (int i = 1; i <= per_move; ++i) out.push_back(at + (m.to - at) * (double(i) / per_move));
      at = m.to;
    }
  return out;
}

}  // namespace cloudtest
