// Slicing benchmark (issue 3): every model of ../shared/data/stl at step 0.1 mm and at 100 layers, plus a
// generated 2M-triangle closed wavy height field. Prints layers, contours, open chains, points and seconds
// (median of 3 runs of slice_mesh alone, the mesh already loaded) next to the reference figures.
// Usage: bench_slice [STL_DIR]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/slice/slicer.hpp"

using namespace rosmill;

namespace {

// A closed solid: the height field z = 10 + 7.5 sin(10 pi x / L) cos(8 pi y / L) over an n x n grid of [0, L]^2
// (2 n^2 triangles, the peaks on grid points so Zmax = 17.5), vertical walls down to z = 0 and a bottom fan.
Mesh wavy_solid(int n, double length) {
  auto height = [&](int i, int j) {
    return 10.0 + 7.5 * std::sin(2 * M_PI * 5 * i / n) * std::cos(2 * M_PI * 4 * j / n);
  };
  auto top = [&](int i, int j) { return Vec3(length * i / n, length * j / n, height(i, j)); };
  auto low = [&](int i, int j) { return Vec3(length * i / n, length * j / n, 0.0); };
  std::vector<Vec3> c;
  c.reserve(3 * (2 * size_t(n) * n + 12 * size_t(n)));
  auto tri = [&](const Vec3& a, const Vec3& b, const Vec3& d) { c.push_back(a), c.push_back(b), c.push_back(d); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      tri(top(i, j), top(i + 1, j), top(i + 1, j + 1));
      tri(top(i, j), top(i + 1, j + 1), top(i, j + 1));
    }
  // The boundary walked counter-clockwise seen from +Z: walls face outwards, the bottom fan faces down.
  std::vector<std::pair<int, int>> ring;
  for (int k = 0; k < n; ++k) ring.emplace_back(k, 0);
  for (int k = 0; k < n; ++k) ring.emplace_back(n, k);
  for (int k = n; k > 0; --k) ring.emplace_back(k, n);
  for (int k = n; k > 0; --k) ring.emplace_back(0, k);
  const Vec3 centre(length / 2, length / 2, 0.0);
  for (size_t k = 0; k < ring.size(); ++k) {
    const auto [i0, j0] = ring[k];
    const auto [i1, j1] = ring[(k + 1) % ring.size()];
    tri(low(i0, j0), low(i1, j1), top(i1, j1));
    tri(low(i0, j0), top(i1, j1), top(i0, j0));
    tri(centre, low(i1, j1), low(i0, j0));
  }
  return build_mesh(c);
}

struct Run {
  SliceSummary summary;
  double seconds;
};

Run time_slicing(const Mesh& mesh, const std::vector<double>& planes) {
  std::vector<double> times;
  SliceSummary s;
  for (int k = 0; k < 3; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<SliceLayer> layers = slice_mesh(mesh, planes);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    s = summarize(layers);
  }
  std::sort(times.begin(), times.end());
  return {s, times[1]};
}

// The reference table: the faster of CGAL Polygon_mesh_slicer and VTK vtkCutter + vtkStripper.
double reference_seconds(const std::string& model, bool by_step) {
  if (model == "counter.unitsmm.STL" && by_step) return 0.351;
  if (model == "demo2.stl.gz" && by_step) return 0.356;
  if (model == "wavy-2M" && by_step) return 8.76;
  if (model == "wavy-2M" && !by_step) return 5.25;
  return NAN;
}

void row(const std::string& name, const Mesh& mesh, bool by_step) {
  const std::vector<double> planes = by_step ? planes_by_step(mesh, 0.1) : planes_by_count(mesh, 100);
  const Run r = time_slicing(mesh, planes);
  const double ref = reference_seconds(name, by_step);
  std::printf("%-22s %9zu %-9s %6zu %9zu %6zu %10zu %9.4f", name.c_str(), mesh.faces.size(),
              by_step ? "step 0.1" : "100", r.summary.layers, r.summary.contours, r.summary.open_contours,
              r.summary.points, r.seconds);
  if (std::isnan(ref))
    std::printf("        -       -\n");
  else
    std::printf(" %8.3f %6.1fx\n", ref, ref / r.seconds);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ROSMILL_SHARED_DATA "/stl";
  std::printf("%-22s %9s %-9s %6s %9s %6s %10s %9s %8s %7s\n", "model", "triangles", "planes", "layers", "contours",
              "open", "points", "seconds", "ref", "speedup");
  std::vector<std::string> files;
  if (std::filesystem::is_directory(dir))
    for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  for (const std::string& f : files) {
    try {
      const Mesh mesh = read_stl(dir + "/" + f);
      row(f, mesh, true);
      row(f, mesh, false);
    } catch (const Error& e) {
      std::printf("%-22s skipped: %s\n", f.c_str(), e.what());
    }
  }
  const Mesh wavy = wavy_solid(1000, 200.0);
  row("wavy-2M", wavy, true);
  row("wavy-2M", wavy, false);
  return 0;
}
