// Where the slice planes go: by step, by count, by the accuracy (the STL slicing paper's rule), or an explicit list.
#include <algorithm>
#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/work_bound.hpp"
#include "rosmill/slice/slicer.hpp"

namespace rosmill::core {
namespace {

void check_mesh(const Mesh& mesh, const std::string& where) {
  if (mesh.faces.empty() || mesh.bbox.empty()) throw Error(where, "the mesh is empty: nothing to slice");
}

// A plane's section crosses about the square root of the mesh's triangles (a surface of n triangles is about
// sqrt(n) of them across); every plane is held.
void check_planes(const Mesh& mesh, double planes, const std::string& where) {
  check_work(where, {planes * std::sqrt(double(mesh.faces.size())), planes, count_text(planes, "planes"),
                     "plane-triangle intersections"},
             mesh.bbox.size().x(), mesh.bbox.size().y());
}

void check_positive(double v, const std::string& where, const char* what) {
  if (!std::isfinite(v) || !(v > 0.0)) throw Error(where, std::string(what) + " must be a positive number");
}

}  // namespace

std::vector<double> planes_by_step(const Mesh& mesh, double step, const std::string& where) {
  check_mesh(mesh, where);
  check_positive(step, where, "the step");
  const double z0 = mesh.bbox.min.z(), range = mesh.bbox.max.z() - z0;
  // A relative slack so that a range that is a whole number of steps keeps its top plane despite rounding.
  const double count = std::floor(range / step * (1.0 + 1e-12) + 1e-12);
  check_planes(mesh, count, where);
  std::vector<double> z;
  z.reserve(size_t(count));
  for (size_t k = 1; k <= size_t(count); ++k) z.push_back(std::min(z0 + double(k) * step, mesh.bbox.max.z()));
  return z;
}

std::vector<double> planes_by_count(const Mesh& mesh, int n, const std::string& where) {
  check_mesh(mesh, where);
  if (n <= 0) throw Error(where, "the number of layers must be a positive integer");
  check_planes(mesh, n, where);
  const double z0 = mesh.bbox.min.z(), range = mesh.bbox.max.z() - z0;
  std::vector<double> z(static_cast<size_t>(n), 0.0);
  for (int k = 1; k <= n; ++k) z[size_t(k - 1)] = z0 + range * double(k) / double(n + 1);
  return z;
}

std::vector<double> planes_by_accuracy(const Mesh& mesh, double accuracy, const std::string& where) {
  check_mesh(mesh, where);
  check_positive(accuracy, where, "the accuracy");
  const double z0 = mesh.bbox.min.z(), range = mesh.bbox.max.z() - z0;
  const double intervals = std::max(1.0, std::ceil(range / accuracy * (1.0 - 1e-12)));
  check_planes(mesh, intervals + 1, where);
  // Zmin and Zmax included: intervals + 1 planes, the interval range / intervals <= accuracy.
  std::vector<double> z;
  const size_t n = size_t(intervals);
  for (size_t k = 0; k <= n; ++k) z.push_back(k == n ? mesh.bbox.max.z() : z0 + range * double(k) / double(n));
  return z;
}

std::vector<double> planes_from_list(std::vector<double> z, const std::string& where) {
  if (z.empty()) throw Error(where, "no plane heights given");
  for (double v : z)
    if (!std::isfinite(v)) throw Error(where, "plane heights must be finite numbers");
  std::sort(z.begin(), z.end());
  return z;
}

}  // namespace rosmill::core
