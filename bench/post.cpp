// Post-processor benchmark (issue 7, point 8):
//  1. post-processing 1M moves (a dense zig-zag over a wavy surface: every block changes X and Z, half of them Y)
//     into a LinuxCNC program, lines only and with arc fitting; target <= 0.5 s for the lines. Median of 3, wall
//     clock and CPU seconds (CPU stays meaningful when other jobs share the two cores).
//  2. the block reduction of arc fitting on the seed primitives' contour toolpaths (strategy "contour", flat end
//     mill 6 mm, step-down 5 mm): motion blocks without and with arcs, at the default 0.005 mm and at 0.02 mm.
// Usage: bench_post

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "cpu_time.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/heap_reuse.hpp"

using namespace rosmill::core;

namespace {

struct Timing {
  double seconds, cpu_seconds;
};

Timing median_of_3(const std::function<void()>& work) {
  std::vector<double> wall, cpu;
  for (int k = 0; k < 3; ++k) {
    const double c0 = cpu_seconds_used();
    const auto t0 = std::chrono::steady_clock::now();
    work();
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(cpu_seconds_used() - c0);
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  return {wall[1], cpu[1]};
}

// `moves` feed moves: zig-zag rows 0.1 mm apart over z = 2 sin(x/7) cos(y/11), one point per 0.05 mm.
Job wavy_raster(size_t moves) {
  Toolpath tp;
  tp.strategy = "raster";
  tp.tool.id = 1;
  tp.tool.cutter = Cutter::ball(6);
  tp.tool.spindle_rpm = 12000;
  tp.clearance_z = 20;
  tp.safe_z = 10;
  tp.start = Vec3(0, 0, 20);
  ToolpathPass pass;
  pass.name = "raster";
  pass.moves.reserve(moves + 2);
  pass.moves.push_back({Vec3(0, 0, 10), MoveType::Rapid, 0});
  const int per_row = 2000;
  for (size_t i = 0; pass.moves.size() < moves + 1; ++i) {
    const size_t row = i / per_row, k = i % per_row;
    const double x = 0.05 * double(row % 2 ? per_row - 1 - k : k), y = 0.1 * double(row);
    const double z = 2 * std::sin(x / 7) * std::cos(y / 11) - 3;
    pass.moves.push_back({Vec3(x, y, z), i == 0 ? MoveType::Plunge : MoveType::Feed, i == 0 ? 300.0 : 1500.0});
  }
  pass.moves.push_back({Vec3(pass.moves.back().to.x(), pass.moves.back().to.y(), 10), MoveType::Rapid, 0});
  tp.passes.push_back(std::move(pass));
  return {tp};
}

void bench_million_moves() {
  const Job job = wavy_raster(1000000);
  size_t moves = 0;
  for (const Toolpath& tp : job) moves += tp.move_count();
  std::printf("post-processing %zu moves (wavy zig-zag, linuxcnc dialect)\n", moves);
  for (bool arcs : {false, true}) {
    gcode::PostOptions o;
    o.arcs = arcs;
    size_t lines = 0, blocks = 0, bytes = 0;
    const Timing t = median_of_3([&] {
      const gcode::Program p = gcode::post(job, o);
      lines = p.lines.size();
      blocks = p.motion_blocks();
      bytes = 0;
      for (const auto& l : p.lines) bytes += l.size() + 1;
    });
    std::printf("  %-10s %8zu lines %8zu motion blocks %6.1f MB  %.3f s wall  %.3f s cpu%s\n",
                arcs ? "with arcs" : "lines", lines, blocks, double(bytes) / 1e6, t.seconds, t.cpu_seconds,
                arcs ? "" : "  (target <= 0.5 s)");
  }
}

void bench_arc_reduction() {
  std::printf("arc fitting on the seed primitives' contour toolpaths (flat end mill 6 mm, step-down 5 mm)\n");
  std::printf("  %-9s %7s %12s %23s %23s\n", "primitive", "moves", "line blocks", "arcs 0.005 mm", "arcs 0.02 mm");
  for (const std::string& name : primitive_names()) {
    const Mesh mesh = make_primitive(name);
    PlanningRequest r;
    r.input.mesh = &mesh;
    r.strategy = "contour";
    PlanParams& params = r.params;
    params.tool.id = 1;
    params.tool.cutter = Cutter::flat(6);
    params.tool.spindle_rpm = 12000;
    params.tool.feed = 800;
    params.tool.plunge_feed = 200;
    params.stepdown = 5;
    const Job job = plan(r);
    size_t moves = 0;
    for (const Toolpath& tp : job) moves += tp.move_count();
    gcode::PostOptions lines_only;
    const size_t base = gcode::post(job, lines_only).motion_blocks();
    std::printf("  %-9s %7zu %12zu", name.c_str(), moves, base);
    for (double tol : {0.005, 0.02}) {
      gcode::PostOptions o;
      o.arcs = true;
      o.arc_tolerance = tol;
      const size_t fitted = gcode::post(job, o).motion_blocks();
      std::printf(" %8zu (%5.1f%% fewer)", fitted, 100.0 * (1.0 - double(fitted) / double(base)));
    }
    std::printf("\n");
  }
}

}  // namespace

int main() {
  rosmill::core::keep_freed_memory();  // repeated jobs reuse their memory (see heap_reuse.hpp)
  bench_million_moves();
  bench_arc_reduction();
  return 0;
}
