// A block with a pocket whose vertical inner corners are rounded (a milled pocket's shape): the part on which rest
// machining has a known answer. A 10 mm end mill cannot follow a corner of radius 3 mm; a 3 mm ball can.
#pragma once
#include <cmath>
#include <vector>

#include "rosmill/geometry/mesh.hpp"

namespace pocket_test {

using rosmill::core::Vec2;
using rosmill::core::Vec3;

struct PocketShape {
  double width = 50, depth = 40, height = 20;  // the block [0, width] x [0, depth] x [0, height]
  double pocket_x = 30, pocket_y = 20;         // the pocket's size, centred
  double pocket_depth = 6, corner_radius = 3;
  int arc_segments = 8;                        // per quarter circle
};

// The pocket's outline at the top, counter-clockwise seen from above.
inline std::vector<Vec2> pocket_outline(const PocketShape& s) {
  const Vec2 c(0.5 * s.width, 0.5 * s.depth);
  const double hx = 0.5 * s.pocket_x - s.corner_radius, hy = 0.5 * s.pocket_y - s.corner_radius;
  const Vec2 centres[4] = {c + Vec2(hx, -hy), c + Vec2(hx, hy), c + Vec2(-hx, hy), c + Vec2(-hx, -hy)};
  std::vector<Vec2> loop;
  for (int q = 0; q < 4; ++q)
    for (int k = 0; k <= s.arc_segments; ++k) {
      const double a = (q - 1) * M_PI / 2 + k * (M_PI / 2) / s.arc_segments;
      loop.push_back(centres[q] + s.corner_radius * Vec2(std::cos(a), std::sin(a)));
    }
  return loop;
}

// Corners (3 per triangle, outward normals) of the closed block with its pocket. The top face is the ring between
// the block's outline and the pocket's, each pocket point joined to the point of the block's outline on the same
// ray from the centre (and the block's corners where a ray passes one), so no edge ends on another's middle.
inline std::vector<Vec3> pocket_corners(const PocketShape& s = {}) {
  const std::vector<Vec2> in = pocket_outline(s);
  const Vec2 c(0.5 * s.width, 0.5 * s.depth);
  const double T = s.height, F = s.height - s.pocket_depth;
  // The point of the block's outline on the ray from the centre through p.
  auto on_block = [&](const Vec2& p) {
    const Vec2 d = p - c;
    const double t = std::min(std::abs(d.x()) > 0 ? 0.5 * s.width / std::abs(d.x()) : INFINITY,
                              std::abs(d.y()) > 0 ? 0.5 * s.depth / std::abs(d.y()) : INFINITY);
    return Vec2(c + t * d);
  };
  const Vec2 block[4] = {{s.width, 0}, {s.width, s.depth}, {0, s.depth}, {0, 0}};
  auto angle = [&](const Vec2& p) { return std::atan2(p.y() - c.y(), p.x() - c.x()); };
  auto between = [](double a, double lo, double hi) {  // a on the counter-clockwise arc from lo to hi
    auto wrap = [](double x) { return x < 0 ? x + 2 * M_PI : x; };
    return wrap(a - lo) > 0 && wrap(a - lo) < wrap(hi - lo);
  };
  std::vector<Vec3> t;
  auto tri = [&](const Vec3& a, const Vec3& b, const Vec3& d) { t.insert(t.end(), {a, b, d}); };
  auto at = [](const Vec2& p, double z) { return Vec3(p.x(), p.y(), z); };
  std::vector<Vec2> out;  // the block's outline, counter-clockwise, with the rays' points and its corners
  const size_t n = in.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 &p = in[i], &q = in[(i + 1) % n];
    const Vec2 P = on_block(p), Q = on_block(q);
    out.push_back(P);
    Vec2 from = P;
    for (const Vec2& k : block)
      if (between(angle(k), angle(p), angle(q))) {
        tri(at(p, T), at(from, T), at(k, T));
        out.push_back(k);
        from = k;
      }
    tri(at(p, T), at(from, T), at(Q, T));
    tri(at(p, T), at(Q, T), at(q, T));
    // The pocket's wall (facing the pocket's inside) and its floor (a fan from the centre).
    tri(at(p, T), at(q, T), at(q, F));
    tri(at(p, T), at(q, F), at(p, F));
    tri(at(c, F), at(p, F), at(q, F));
  }
  // The block's walls (facing out) and its bottom (facing down).
  for (size_t k = 0; k < out.size(); ++k) {
    const Vec2 &a = out[k], &b = out[(k + 1) % out.size()];
    tri(at(a, T), at(a, 0), at(b, 0));
    tri(at(a, T), at(b, 0), at(b, T));
    tri(at(c, 0), at(b, 0), at(a, 0));
  }
  return t;
}

}  // namespace pocket_test
