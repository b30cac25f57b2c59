// Verification speed: a 1M-move finishing program on a 1000 x 1000 grid (issue 9, target <= 2 s on 2 cores).
// The program is a zig-zag raster of a ball over the dome primitive, its cutter locations exact for the true
// sphere, written as G-code and read back, so the figures cover the reader, the simulation and the comparison.
// Usage: bench_verify [threads [case]]   (case: 1, 2 or 3 runs that one only)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include <tbb/global_control.h>

#include "cpu_time.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/verify/gcode_reader.hpp"
#include "rosmill/verify/verify.hpp"
#include "rosmill/heap_reuse.hpp"
#include "rosmill/seconds_since.hpp"

using namespace rosmill::core;
using namespace rosmill::core::verify;
using namespace rosmill::core::stock;

namespace {

using Clock = std::chrono::steady_clock;

struct Case {
  const char* name;
  double dome_radius;  // mm; the grid spans the dome's diameter in 1000 cells
  double ball;         // cutter diameter, mm
  int lines;           // raster lines; lines x moves_per_line = 1M moves
  int moves_per_line;
};

const Case kCases[] = {
    {"dome r50, ball 6, 0.1 mm cells", 50, 6, 250, 4000},
    {"dome r50, ball 2, 0.1 mm cells", 50, 2, 250, 4000},
    {"dome r125, ball 6, 0.25 mm cells", 125, 6, 500, 2000},
};

// Raster along x over [-r, r]^2: `lines` lines, each of `moves` feed moves following the sphere offset by the
// ball's radius (tip = centre - R), down to the table (z 0) outside the dome.
std::string raster_program(double r, double ball, int lines, int moves) {
  const double R = 0.5 * ball, step = 2 * r / (lines - 1), dx = 2 * r / moves;
  std::ostringstream g;
  g.precision(6);
  g << std::fixed << "G21 G90 G17\nT1 M6\nG0 X" << -r << " Y" << -r << " Z" << r + 10 << "\n";
  for (int k = 0; k < lines; ++k) {
    const double y = -r + k * step;
    for (int q = k == 0 ? 0 : 1; q <= moves; ++q) {
      const double x = k % 2 ? r - q * dx : -r + q * dx, rho2 = x * x + y * y;
      const double z = std::max(0.0, std::sqrt(std::max(0.0, (r + R) * (r + R) - rho2)) - R);
      g << "G1 X" << x << " Y" << y << " Z" << z << (k == 0 && q == 0 ? " F1000" : "") << "\n";
    }
  }
  g << "G0 Z" << r + 10 << "\nM30\n";
  return g.str();
}

}  // namespace

int main(int argc, char** argv) {
  rosmill::core::keep_freed_memory();  // repeated jobs reuse their memory (see heap_reuse.hpp)
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  const int only = argc > 2 ? std::atoi(argv[2]) : 0;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::printf("threads %d; read = G-code text to moves; simulate = material removal; verify = grid, design heights,\n"
              "simulation and comparison together (wall, and CPU of all threads); footprint = cells one move's cutter covers;\nvisited = cells the simulation evaluated per move\n",
              threads);
  std::printf("%-34s %8s %6s %9s %8s %7s %10s %8s %8s %8s %9s\n", "case", "moves", "cells", "footprint", "visited", "read s",
              "simulate s", "verify s", "CPU s", "scallop", "max gouge");
  int number = 0;
  for (const Case& c : kCases) {
    if (++number != only && only != 0) continue;
    const std::string text = raster_program(c.dome_radius, c.ball, c.lines, c.moves_per_line);
    auto t0 = Clock::now();
    const MachineProgram program = parse_gcode(text, "bench.ngc", tool_setup({"1=ball:" + std::to_string(c.ball)}));
    const double read = seconds_since(t0);
    const Mesh dome = build_mesh(dome_corners(c.dome_radius));
    StockSpec stock;
    stock.kind = StockSpec::Kind::Box;
    stock.box.add(Vec3(-c.dome_radius, -c.dome_radius, 0));
    stock.box.add(Vec3(c.dome_radius, c.dome_radius, c.dome_radius + 2));
    VerifyOptions o;
    o.resolution = 2 * c.dome_radius / 1000;
    o.compare.stepover = 2 * c.dome_radius / (c.lines - 1);
    const double cpu0 = cpu_seconds_used();
    const VerifyResult r = verify_program(dome, program, stock, o);
    const double cpu = cpu_seconds_used() - cpu0;
    const double footprint = M_PI * 0.25 * c.ball * c.ball / (o.resolution * o.resolution);
    std::printf("%-34s %8zu %6s %9.0f %8.1f %7.3f %10.3f %8.3f %8.3f %8.4f %9.4f\n", c.name, program.moves.size(),
                r.report.cells == 1000000 ? "1000^2" : "?", footprint,
                static_cast<double>(r.cells_visited) / program.moves.size(), read, r.simulation_seconds, r.seconds, cpu,
                r.report.scallop_mm, r.report.max_gouge_mm);
  }
  return 0;
}
