#include "rosmill/scan/surface_sample.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "rosmill/error.hpp"

namespace rosmill::core::scan {

SurfaceSample sample_surface(const Mesh& mesh, size_t count, uint64_t seed) {
  check_has_area(mesh, "surface sampling");
  if (count == 0) throw Error("surface sampling", "the number of points must be positive");
  std::vector<double> cumulative(mesh.face_count());
  double total = 0;
  for (size_t f = 0; f < mesh.face_count(); ++f) cumulative[f] = total += mesh.areas[f];
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  SurfaceSample s;
  s.points.reserve(count);
  s.normals.reserve(count);
  s.faces.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    // A face by its share of the area; degenerate faces (zero area) are never drawn.
    const double at = uniform(rng) * total;
    const size_t f = std::min<size_t>(size_t(std::upper_bound(cumulative.begin(), cumulative.end(), at) -
                                             cumulative.begin()), mesh.face_count() - 1);
    // Uniform on the triangle: the square root folds the unit square onto it without crowding a corner.
    const double r1 = std::sqrt(uniform(rng)), r2 = uniform(rng);
    const Vec3 &a = mesh.corner(f, 0), &b = mesh.corner(f, 1), &c = mesh.corner(f, 2);
    s.points.push_back((1 - r1) * a + r1 * (1 - r2) * b + r1 * r2 * c);
    s.normals.push_back(mesh.normals[f]);
    s.faces.push_back(uint32_t(f));
  }
  return s;
}

}  // namespace rosmill::core::scan
