// Segmentation speed on the table: phase 1 (flood + recombination + patch records) and phase 2 for one
// setup (+Z: EGI of every patch, pruning, recombination, segment records), median of 3 after a first run, the
// mesh already loaded, threshold 0.4 (23.07 degrees). Models: every STL of ../shared/data/stl and a generated
// 2,012,000-
// triangle closed wavy solid. Usage: bench_segment [threads]
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "rosmill/error.hpp"
#include "rosmill/testing/wavy_solid.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/segment/setup_segmentation.hpp"
#include "rosmill/heap_reuse.hpp"

using namespace rosmill::core;
using namespace rosmill::core::segment;

namespace {

struct Model {
  std::string name;
  double cgal_seconds;  // the CGAL detect_sharp_edges + connected_components figure (0: none given)
};

const Model kModels[] = {
    {"failedinpycam.stl", 0}, {"pycam-textbox.stl", 0}, {"featuretype.STL", 0},      {"ktoolcav.stl", 0},
    {"wheel_in_box.stl", 0},  {"mount_rush.stl", 0},    {"counter.unitsmm.STL", 0.0084}, {"demo2.stl.gz", 0.0070},
};

// One untimed first run (fresh pages on this VM class cost 2-8 ms per MB, see heap_reuse.hpp), then the median
// of `runs`: the figures of a node segmenting part after part, as bench_stl_load reports loads.
double median_seconds(int runs, const std::function<void()>& work) {
  work();
  std::vector<double> t;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    work();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}


void run(const std::string& name, const Mesh& mesh, double cgal) {
  SurfacePatches sp;
  // The last result is released before each run, so that a run reuses its memory.
  const double t1 = median_seconds(3, [&] {
    sp = SurfacePatches();
    sp = segment_surface(mesh);
  });
  size_t segments = 0;
  const double t2 = median_seconds(3, [&] {
    const EgiSet egis(sp);
    segments = segment_setup(egis, parse_setup("+z")).count();
  });
  const EgiSet egis(sp);
  const double t2s = median_seconds(3, [&] { segment_setup(egis, parse_setup("+z")); });
  char ref[32] = "-";
  if (cgal > 0) std::snprintf(ref, sizeof ref, "%.4f (%.2fx)", cgal, t1 / cgal);
  std::printf("%-20s %9zu %8zu %8zu %9.4f %16s %9.4f %9.4f %6zu %s\n", name.c_str(), mesh.face_count(),
              sp.notes().patches_before_recombination, sp.count(), t1, ref, t2, t2s, segments,
              mesh.closed() ? "closed" : "open");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  rosmill::core::keep_freed_memory();  // repeated jobs reuse their memory (see heap_reuse.hpp)
  using tbb::global_control;
  const size_t threads = argc > 1 ? size_t(std::max(1, std::atoi(argv[1])))
                                  : global_control::active_value(global_control::max_allowed_parallelism);
  const global_control limit(global_control::max_allowed_parallelism, threads);
  std::printf("threads %zu; seconds, median of 3, mesh loaded; phase2 = EGI + +Z pruning + recombination, setup = "
              "+Z alone on a built EGI\n", threads);
  std::printf("%-20s %9s %8s %8s %9s %16s %9s %9s %6s\n", "model", "tris", "flooded", "patches", "phase1",
              "CGAL (phase1/)", "phase2", "setup", "segs");
  for (const Model& m : kModels) {
    const std::string path = std::string(ROSMILL_SHARED_DATA) + "/stl/" + m.name;
    try {
      const Mesh mesh = read_stl(path);
      run(m.name, mesh, m.cgal_seconds);
    } catch (const Error& e) {
      std::printf("%-20s skipped: %s\n", m.name.c_str(), e.what());
    }
  }
  const Mesh wavy = build_mesh(wavy_solid_corners());
  run("2M wavy solid", wavy, 0.109);
  return 0;
}
