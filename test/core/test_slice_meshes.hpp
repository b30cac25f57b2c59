// Hand-built meshes for the slicing tests and bench: boxes, an L-shaped step, a closed wavy height field.
#pragma once
#include <cmath>
#include <utility>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/testing/wavy_solid.hpp"

namespace slice_test {
using rosmill::core::Vec3;

inline void tri(std::vector<Vec3>& out, const Vec3& a, const Vec3& b, const Vec3& c) {
  out.push_back(a);
  out.push_back(b);
  out.push_back(c);
}

// Reverses every triangle when the closed mesh's volume is negative, so normals point out.
inline rosmill::core::Mesh outward(std::vector<Vec3> corners) {
  rosmill::core::Mesh m = rosmill::core::build_mesh(corners);
  if (rosmill::core::report(m).volume < 0) {
    for (size_t i = 0; i < corners.size(); i += 3) std::swap(corners[i + 1], corners[i + 2]);
    m = rosmill::core::build_mesh(corners);
  }
  return m;
}

// Corners of a box [lo, hi] (12 triangles, outward when lo < hi componentwise).
inline std::vector<Vec3> box_corners(const Vec3& lo, const Vec3& hi) {
  std::vector<Vec3> cube = rosmill::core::cube_corners(1.0);
  for (Vec3& p : cube) p = lo + p.cwiseProduct(hi - lo);
  return cube;
}

// An L-shaped step extruded along Y over [0, 60]: the block [0,60]x[0,60]x[0,30] with [0,30]x[0,60]x[30,60]
// on top; the step's top face (z = 30, x in [30, 60]) is 30 x 60 = 1800 mm².
inline rosmill::core::Mesh step_block() {
  const double px[6] = {0, 60, 60, 30, 30, 0}, pz[6] = {0, 0, 30, 30, 60, 60};
  std::vector<Vec3> c;
  const int fan[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  for (auto& t : fan) {
    tri(c, {px[t[0]], 0, pz[t[0]]}, {px[t[1]], 0, pz[t[1]]}, {px[t[2]], 0, pz[t[2]]});
    tri(c, {px[t[0]], 60, pz[t[0]]}, {px[t[2]], 60, pz[t[2]]}, {px[t[1]], 60, pz[t[1]]});
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    const Vec3 a(px[i], 0, pz[i]), b(px[j], 0, pz[j]), a1(px[i], 60, pz[i]), b1(px[j], 60, pz[j]);
    tri(c, a, a1, b1);
    tri(c, a, b1, b);
  }
  return outward(c);
}

// A closed solid: the height field z = 10 + 7.5 sin(10 pi x / L) cos(8 pi y / L) over an n x n grid of [0, L]^2
// (2 n^2 triangles, the peaks on grid points so Zmax = 17.5), vertical walls down to z = 0 and a bottom fan.
inline rosmill::core::Mesh wavy_solid(int n, double length) {
  return rosmill::core::build_mesh(rosmill::core::wavy_solid_corners(n, length));
}

}  // namespace slice_test
