// Drop-cutter rate on the table (OpenCAMLib BatchDropCutter, 2 threads, same models, cutters and point
// counts) and a check of a subsample against the independent reference (cutter/reference_drop: its own
// concave-maximisation over every triangle, no code shared with the drop-cutter). Usage: bench_dropcutter [threads]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "rosmill/testing/reference_drop.hpp"
#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/drop_grid.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/heap_reuse.hpp"

using namespace rosmill::core;

namespace {

struct Row {
  const char* file;
  const char* tool;
  size_t points;        // OpenCAMLib's CL point count
  double ocl_rate;      // OpenCAMLib's points per second
};

const Row kRows[] = {
    {"failedinpycam.stl", "ball:6", 1002001, 99660},  {"pycam-textbox.stl", "ball:6", 1000878, 64187},
    {"wheel_in_box.stl", "ball:6", 1000000, 73449},   {"mount_rush.stl", "ball:6", 250344, 15481},
    {"mount_rush.stl", "flat:10", 250656, 12866},     {"counter.unitsmm.STL", "ball:6", 1001000, 54525},
    {"demo2.stl.gz", "ball:6", 105280, 5404},         {"demo2.stl.gz", "flat:10", 63495, 3226},
    {"ktoolcav.stl", "ball:6", 46872, 2164},
};

// The spacing whose grid holds the closest number of points to `target` (the count falls as the step grows).
double spacing_for(const Box3& box, double radius, size_t target) {
  double lo = 1e-3 * radius, hi = 1e4;
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (grid_over(box, radius, mid).size() > target ? lo : hi) = mid;
  }
  const size_t a = grid_over(box, radius, lo).size(), b = grid_over(box, radius, hi).size();
  return (a > target ? a - target : target - a) < (b > target ? b - target : target - b) ? lo : hi;
}

}  // namespace

int main(int argc, char** argv) {
  rosmill::core::keep_freed_memory();  // repeated jobs reuse their memory (see heap_reuse.hpp)
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::printf("threads %d; seconds = index build + all drops; check: of 2000 points, equal to the reference within 1e-6 / rim ties (see reference_drop.hpp) / different\n",
              threads);
  std::printf("%-20s %7s %-8s %9s %8s %10s %10s %6s %s\n", "model", "tris", "cutter", "points", "seconds",
              "points/s", "OCL pts/s", "xOCL", "equal/tie/diff");
  for (const Row& row : kRows) {
    const std::string path = std::string(ROSMILL_SHARED_DATA) + "/stl/" + row.file;
    Mesh mesh;
    try {
      mesh = read_stl(path);
      if (mesh.face_count() == 0) throw Error(path, "no triangles read");
    } catch (const Error& e) {
      std::printf("%-20s skipped: %s\n", row.file, e.what());
      continue;
    }
    const Cutter cutter = parse_cutter_spec(row.tool);
    const DropGrid grid = grid_over(mesh.bbox, cutter.radius(), spacing_for(mesh.bbox, cutter.radius(), row.points));
    const auto t0 = std::chrono::steady_clock::now();
    const MeshSurface surface(mesh);
    const std::vector<Vec3> cl = drop_grid(surface, cutter, grid, mesh.bbox.min.z());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The check runs after the timing, on both cores: the reference is thousands of times slower.
    // Points spread by the golden ratio: a plain stride would fall on a few grid columns only.
    std::vector<ReferenceCheck> checks(std::min<size_t>(2000, cl.size()));
    tbb::parallel_for(size_t(0), checks.size(), [&](size_t i) {
      const double where = std::fmod(0.6180339887498949 * double(i), 1.0);
      const Vec3& p = cl[std::min(cl.size() - 1, static_cast<size_t>(where * double(cl.size())))];
      checks[i] = check_drop(cutter, mesh, p.x(), p.y(), p.z(), mesh.bbox.min.z(), 1e-6);
    });
    // Every point that is not equal, exactly, so that it can be turned into a test.
    for (size_t i = 0; i < checks.size(); ++i) {
      if (checks[i] == ReferenceCheck::Equal) continue;
      const double where = std::fmod(0.6180339887498949 * double(i), 1.0);
      const Vec3& p = cl[std::min(cl.size() - 1, static_cast<size_t>(where * double(cl.size())))];
      std::printf("  %s at x %.17g y %.17g: drop %.17g, reference %.17g\n",
                  checks[i] == ReferenceCheck::RimTie ? "rim tie" : "differs", p.x(), p.y(), p.z(),
                  std::max(reference_drop(cutter, mesh, p.x(), p.y()), mesh.bbox.min.z()));
    }
    const auto count = [&](ReferenceCheck c) { return std::count(checks.begin(), checks.end(), c); };
    const double rate = cl.size() / seconds;
    const long differ = count(ReferenceCheck::Differs);
    std::printf("%-20s %7zu %-8s %9zu %8.3f %10.0f %10.0f %6.1f %ld/%ld/%ld%s\n", row.file, mesh.face_count(),
                row.tool, cl.size(), seconds, rate, row.ocl_rate, rate / row.ocl_rate, count(ReferenceCheck::Equal),
                count(ReferenceCheck::RimTie), differ, differ == 0 ? "" : " FAIL");
  }
  return 0;
}
