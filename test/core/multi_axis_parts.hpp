// Test parts for multi-axis finishing, closed, in millimetres: a hemisphere standing on a square plate, and a
// cylinder standing on its end.
#pragma once
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/primitives.hpp"

namespace test_parts {

using rosmill::core::Box3;
using rosmill::core::Mesh;
using rosmill::core::Vec3;

// A UV sphere's upper half (radius r, centre at the origin) on a square base plate of half-width w and thickness t
// below z = 0, closed: the dome's facets, a flat ring round it and the plate's sides and bottom.
inline Mesh dome_on_plate(double r, double w, double t, int segments = 144, int rings = 48) {
  std::vector<Vec3> c;
  auto tri = [&](const Vec3& a, const Vec3& b, const Vec3& d) { c.insert(c.end(), {a, b, d}); };
  auto at = [&](int i, int j) {  // i round, j up from the equator
    // The seam: the last meridian is the first, and the pole one point, to the bit (a sliver between them would
    // open the mesh).
    if (j == rings) return Vec3(0, 0, r);
    const double phi = 2 * M_PI * (i % segments) / segments, th = 0.5 * M_PI * j / rings;
    return Vec3(r * std::cos(th) * std::cos(phi), r * std::cos(th) * std::sin(phi), r * std::sin(th));
  };
  for (int i = 0; i < segments; ++i)
    for (int j = 0; j < rings; ++j) {
      const Vec3 p00 = at(i, j), p10 = at(i + 1, j), p01 = at(i, j + 1), p11 = at(i + 1, j + 1);
      tri(p00, p10, p11);
      if (j + 1 < rings) tri(p00, p11, p01);
    }
  // The plate's top round the dome: a fan from each corner's quarter.
  const Vec3 corner[4] = {Vec3(w, w, 0), Vec3(-w, w, 0), Vec3(-w, -w, 0), Vec3(w, -w, 0)};
  for (int i = 0; i < segments; ++i) {
    const double phi = 2 * M_PI * (i + 0.5) / segments;
    const int q = static_cast<int>(std::floor(std::fmod(phi + 2 * M_PI, 2 * M_PI) / (0.5 * M_PI))) % 4;
    tri(at(i + 1, 0), at(i, 0), corner[q]);
  }
  for (int q = 0; q < 4; ++q) {
    const int i = q * segments / 4;
    tri(at(i, 0), corner[(q + 3) % 4], corner[q]);
  }
  const std::vector<Vec3> box = rosmill::core::box_corners(Box3::between(Vec3(-w, -w, -t), Vec3(w, w, 0)));
  // The box's sides and bottom (its top is the ring above): facets whose normal is not +Z.
  for (size_t k = 0; k < box.size(); k += 3) {
    const Vec3 n = (box[k + 1] - box[k]).cross(box[k + 2] - box[k]);
    if (n.z() > 0.5 * n.norm()) continue;
    tri(box[k], box[k + 1], box[k + 2]);
  }
  return rosmill::core::build_mesh(c);
}

// The dome (radius 15 on a plate 36 mm wide) between two walls higher than it along X: where the rule's tool axis
// would put the holder into a wall, the axis must turn.
inline Mesh dome_between_walls() {
  const Mesh dome = dome_on_plate(15, 18, 6, 96, 32);
  std::vector<Vec3> corners;
  for (size_t f = 0; f < dome.face_count(); ++f)
    for (int i = 0; i < 3; ++i) corners.push_back(dome.corner(f, i));
  for (const Box3& wall :
       {Box3::between(Vec3(-30, -30, -6), Vec3(-18, 30, 25)), Box3::between(Vec3(18, -30, -6), Vec3(30, 30, 25))}) {
    const std::vector<Vec3> w = rosmill::core::box_corners(wall);
    corners.insert(corners.end(), w.begin(), w.end());
  }
  return rosmill::core::build_mesh(corners);
}

// A cylinder of radius r from z = 0 to h about the Z axis, its sides in `segments` facets, closed by its ends.
inline Mesh cylinder_standing(double r, double h, int segments = 180) {
  std::vector<Vec3> c;
  auto tri = [&](const Vec3& a, const Vec3& b, const Vec3& d) { c.insert(c.end(), {a, b, d}); };
  auto at = [&](int i, double z) {
    const double phi = 2 * M_PI * i / segments;
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
  };
  for (int i = 0; i < segments; ++i) {
    tri(at(i, 0), at(i + 1, 0), at(i + 1, h));
    tri(at(i, 0), at(i + 1, h), at(i, h));
    tri(Vec3(0, 0, h), at(i, h), at(i + 1, h));
    tri(Vec3(0, 0, 0), at(i + 1, 0), at(i, 0));
  }
  return rosmill::core::build_mesh(c);
}

}  // namespace test_parts
