// Slicing benchmark (issue 3): every model of ../shared/data/stl at step 0.1 mm and at 100 layers, plus a
// generated 2M-triangle closed wavy height field. Prints layers, contours, open chains, points and seconds
// (median of 3 runs of slice_mesh alone, the mesh already loaded) next to the reference figures, and the
// CPU seconds of all threads (median of 3), which stay meaningful when other jobs share the two cores.
// Usage: bench_slice [STL_DIR]
#include <algorithm>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cpu_time.hpp"
#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/slice/slicer.hpp"
#include "../test/core/test_slice_meshes.hpp"
#include "rosmill/heap_reuse.hpp"

using namespace rosmill::core;

namespace {

struct Run {
  SliceSummary summary;
  double seconds;      // wall clock, median of 3
  double cpu_seconds;  // CPU time of all threads, median of 3: what the work costs when other jobs share the cores
};

Run time_slicing(const Mesh& mesh, const std::vector<double>& planes) {
  std::vector<double> times, cpu;
  SliceSummary s;
  for (int k = 0; k < 3; ++k) {
    const double c0 = cpu_seconds_used();
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<SliceLayer> layers = slice_mesh(mesh, planes);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(cpu_seconds_used() - c0);
    s = summarize(layers);
  }
  std::sort(times.begin(), times.end());
  std::sort(cpu.begin(), cpu.end());
  return {s, times[1], cpu[1]};
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
  std::printf("%-22s %9zu %-9s %6zu %9zu %6zu %10zu %9.4f %8.4f", name.c_str(), mesh.faces.size(),
              by_step ? "step 0.1" : "100", r.summary.layers, r.summary.contours, r.summary.open_contours,
              r.summary.points, r.seconds, r.cpu_seconds);
  if (mesh.closed() && r.summary.open_contours > 0) std::printf("  OPEN CHAINS ON A CLOSED MESH");
  if (std::isnan(ref))
    std::printf("        -       -\n");
  else
    std::printf(" %8.3f %6.1fx\n", ref, ref / r.seconds);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  rosmill::core::keep_freed_memory();  // repeated jobs reuse their memory (see heap_reuse.hpp)
  const std::string dir = argc > 1 ? argv[1] : ROSMILL_SHARED_DATA "/stl";
  std::printf("%-22s %9s %-9s %6s %9s %6s %10s %9s %8s %8s %7s\n", "model", "triangles", "planes", "layers",
              "contours", "open", "points", "seconds", "cpu_s", "ref", "speedup");
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
  const Mesh wavy = slice_test::wavy_solid(1000, 200.0);
  row("wavy-2M", wavy, true);
  row("wavy-2M", wavy, false);
  return 0;
}
