#include "rosmill/geometry/corner_normals.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace rosmill::core {
namespace {

// The facet's angle at corner i (radians).
double corner_angle(const Mesh& mesh, size_t f, int i) {
  const Vec3& p = mesh.corner(f, i);
  const Vec3 a = mesh.corner(f, (i + 1) % 3) - p, b = mesh.corner(f, (i + 2) % 3) - p;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

std::vector<std::array<Vec3, 3>> corner_normals(const Mesh& mesh, double crease_deg) {
  const size_t n = mesh.face_count();
  // The facets round each vertex, as offsets into one array (counting sort by vertex).
  std::vector<uint32_t> start(mesh.vertex_count() + 1, 0);
  for (const Mesh::Face& face : mesh.faces)
    for (uint32_t v : face) ++start[v + 1];
  for (size_t v = 0; v < mesh.vertex_count(); ++v) start[v + 1] += start[v];
  std::vector<uint32_t> round(start.back());
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (size_t f = 0; f < n; ++f)
    for (uint32_t v : mesh.faces[f]) round[fill[v]++] = static_cast<uint32_t>(f);
  const double crease_cos = std::cos(crease_deg * M_PI / 180.0);
  std::vector<std::array<Vec3, 3>> out(n);
  for (size_t f = 0; f < n; ++f) {
    const Vec3& own = mesh.normals[f];
    for (int i = 0; i < 3; ++i) {
      const uint32_t v = mesh.faces[f][i];
      Vec3 sum = Vec3::Zero();
      for (uint32_t k = start[v]; k < start[v + 1]; ++k) {
        const uint32_t g = round[k];
        if (mesh.areas[g] <= 0 || mesh.normals[g].dot(own) < crease_cos) continue;
        const int corner = mesh.faces[g][0] == v ? 0 : mesh.faces[g][1] == v ? 1 : 2;
        sum += corner_angle(mesh, g, corner) * mesh.normals[g];
      }
      const double len = sum.norm();
      out[f][i] = len > 0 ? Vec3(sum / len) : own;
    }
  }
  return out;
}

Vec3 smooth_normal(const std::vector<std::array<Vec3, 3>>& normals, uint32_t f, double u, double v) {
  const auto& c = normals[f];
  const Vec3 n = (1 - u - v) * c[0] + u * c[1] + v * c[2];
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : c[0];
}

}  // namespace rosmill::core
