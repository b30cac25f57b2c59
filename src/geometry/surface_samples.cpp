#include "rosmill/geometry/surface_samples.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::core {

double sample_spacing(const Mesh& mesh, double target) {
  double area = 0;
  for (double a : mesh.areas) area += a;
  return std::max(0.05, std::sqrt(area / std::max(1.0, target)));
}

SurfaceSamples sample_surface(const Mesh& mesh, double spacing) {
  if (!(spacing > 0) || !std::isfinite(spacing)) throw Error("samples", "the spacing must be a positive number");
  SurfaceSamples s;
  s.points.reserve(mesh.face_count());
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const double area = mesh.areas[f];
    if (!(area > 0)) continue;
    const Vec3 a = mesh.corner(f, 0), b = mesh.corner(f, 1), c = mesh.corner(f, 2);
    const int m = std::max(1, static_cast<int>(std::ceil(std::sqrt(area) / spacing)));
    const double w = area / (double(m) * m);
    // The m^2 similar triangles of the subdivision: (i, j) up and, but on the last row, (i, j) down.
    const Vec3 u = (b - a) / m, v = (c - a) / m;
    auto add = [&](const Vec3& p) {
      s.points.push_back(p);
      s.normals.push_back(mesh.normals[f]);
      s.weights.push_back(w);
      s.facets.push_back(static_cast<uint32_t>(f));
    };
    for (int i = 0; i < m; ++i)
      for (int j = 0; i + j < m; ++j) {
        add(a + (i + 1.0 / 3) * u + (j + 1.0 / 3) * v);
        if (i + j + 1 < m) add(a + (i + 2.0 / 3) * u + (j + 2.0 / 3) * v);
      }
  }
  return s;
}

}  // namespace rosmill::core
