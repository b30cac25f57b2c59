// Planning times for every model of ../shared/data/stl (the point 8: waterline and roughing, raster
// beside them): seconds to plan (surface index included), moves and cutting length. Inch models are read as
// inches (scaled to mm). Settings: waterline ball 6 every 2 mm down; rough flat 10, stepover 6, step-down 3,
// allowance 0.5; raster ball 6, stepover 1; tolerance 0.001 for all. Usage: bench_plan [threads]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <tbb/global_control.h>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/toolpath/toolpath_stats.hpp"
#include "bundled_models.hpp"

using namespace rosmill::core;

namespace {

using test_data::BundledModel;
using test_data::kBundledModels;

struct Setting {
  const char* strategy;
  Cutter cutter;
  double stepover, stepdown, allowance;
};

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const Setting settings[] = {{"waterline", Cutter::ball(6), 1.0, 2.0, 0.0},
                              {"rough", Cutter::flat(10), 6.0, 3.0, 0.5},
                              {"raster", Cutter::ball(6), 1.0, 2.0, 0.0}};
  std::printf("threads %d; seconds = surface index + planning, wall clock\n", threads);
  std::printf("%-20s %7s %-10s %9s %10s %12s\n", "model", "tris", "strategy", "seconds", "moves", "cutting mm");
  for (const BundledModel& m : kBundledModels) {
    StlReadOptions ro;
    ro.units = m.units;
    Mesh mesh;
    try {
      mesh = read_stl(std::string(ROSMILL_SHARED_DATA) + "/stl/" + m.file, ro);
    } catch (const Error& e) {
      std::printf("%-20s skipped: %s\n", m.file, e.what());
      continue;
    }
    for (const Setting& s : settings) {
      PlanParams p;
      p.tool = default_tool(s.cutter);
      p.stepover = s.stepover;
      p.stepdown = s.stepdown;
      p.allowance = s.allowance;
      PlanningRequest r;
      r.input.mesh = &mesh;
      r.strategy = s.strategy;
      r.params = p;
      const auto t0 = std::chrono::steady_clock::now();
      const Job job = plan(r);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      ToolpathStats total;
      for (const Toolpath& tp : job) {
        const ToolpathStats st = toolpath_stats(tp);
        total.moves += st.moves;
        total.cutting_length += st.cutting_length;
      }
      std::printf("%-20s %7zu %-10s %9.3f %10zu %12.0f\n", m.file, mesh.face_count(), s.strategy, seconds,
                  total.moves, total.cutting_length);
      std::fflush(stdout);
    }
  }
  return 0;
}
