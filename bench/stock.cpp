// The in-process stock under a long program: 1M moves into a 300 x 300 x 100 mm box at 0.25 mm (target <= 3 s on
// 2 cores), for a 6 mm ball finishing raster over a wavy surface and for 10 mm flat roughing levels, with the
// memory (peak RSS, the model's bytes, bytes per mm^3 of stock). Beside it, what tri-dexel stock (three orthogonal
// dexel grids, each move clipping the X and Y dexels its cutter and shank cross as well as the Z ones) would cost:
// the X and Y dexels every move crosses are counted, and the time of one such clip is measured.
// Usage: bench_stock [threads [case]]   (case: 1 or 2 runs that one only)
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <tbb/global_control.h>

#include "cpu_time.hpp"
#include "rosmill/heap_reuse.hpp"
#include "rosmill/seconds_since.hpp"
#include "rosmill/stock/in_process_stock.hpp"

using namespace rosmill::core;
using namespace rosmill::core::stock;

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kSize = 300, kHeight = 100, kCell = 0.25;

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

MachineProgram one_tool(const Cutter& cutter) {
  MachineProgram p;
  p.tools.push_back(Tool{});
  p.tools.back().cutter = cutter;
  return p;
}

void move_to(MachineProgram& p, const Vec3& to, bool rapid = false) {
  CanonMove m;
  m.from = p.moves.empty() ? Vec3(to.x(), to.y(), kHeight + 10) : p.moves.back().to;
  m.to = to;
  m.rapid = rapid;
  m.feed = rapid ? 0.0f : 2000.0f;
  m.source = static_cast<uint32_t>(p.moves.size() + 1);
  p.moves.push_back(m);
}

// Finishing: a zig-zag raster along x of 500 lines, 2000 moves each, the tip on z = 60 + 20 sin(x/25) cos(y/30).
MachineProgram ball_raster() {
  MachineProgram p = one_tool(Cutter::ball(6));
  const int lines = 500, moves = 2000;
  for (int k = 0; k < lines; ++k) {
    const double y = kSize * k / (lines - 1);
    for (int q = 0; q <= moves; ++q) {
      const double x = kSize * (k % 2 ? moves - q : q) / moves;
      const Vec3 at(x, y, 60 + 20 * std::sin(x / 25) * std::cos(y / 30));
      if (k == 0 && q == 0) move_to(p, Vec3(x, y, kHeight + 10), true);
      move_to(p, at);
    }
  }
  move_to(p, Vec3(p.moves.back().to.x(), p.moves.back().to.y(), kHeight + 10), true);
  return p;
}

// Roughing: 10 levels 2 mm apart from the top, each a zig-zag of 61 lines 5 mm apart across the box, each line in
// moves of 0.18 mm (as an adaptive clearing path writes them), a rapid up and over between levels.
MachineProgram flat_roughing() {
  MachineProgram p = one_tool(Cutter::flat(10));
  const int levels = 10, lines = 61, moves = 1639;
  for (int l = 1; l <= levels; ++l) {
    const double z = kHeight - 2 * l;
    move_to(p, Vec3(-6, 0, kHeight + 5), true);
    move_to(p, Vec3(-6, 0, z));
    for (int k = 0; k < lines; ++k) {
      const double y = kSize * k / (lines - 1);
      if (k > 0) move_to(p, Vec3(p.moves.back().to.x(), y, z));
      for (int q = 1; q <= moves; ++q) {
        const double s = (kSize + 12) * q / moves - 6;
        move_to(p, Vec3(k % 2 ? kSize - s : s, y, z));
      }
    }
    move_to(p, Vec3(p.moves.back().to.x(), p.moves.back().to.y(), kHeight + 5), true);
  }
  return p;
}

// X and Y dexels (lines along x at each (y, z) of the lattice, and along y) a move's cutter and shank cross inside
// the stock: those within R of its path across, from its lowest tip up to the stock's top.
double side_dexels_crossed(const MachineProgram& p) {
  double n = 0;
  for (const CanonMove& m : p.moves) {
    const double R = 0.5 * p.tools[m.tool].cutter.diameter;
    const double z0 = std::max(0.0, std::min(m.from.z(), m.to.z())), z1 = kHeight;
    if (z0 >= z1) continue;
    const double across_y = std::abs(m.to.y() - m.from.y()) + 2 * R, across_x = std::abs(m.to.x() - m.from.x()) + 2 * R;
    n += (across_y + across_x) / kCell * (z1 - z0) / kCell;
  }
  return n;
}

// Seconds to clip one dexel by a swept ball (its chord through the capsule around the move, then the span cut):
// the least work a tri-dexel update does per X or Y dexel.
double seconds_per_dexel_clip() {
  const int n = 20'000'000;
  std::vector<Span> spans(1 << 16, Span{0.0f, 100.0f});
  const auto t0 = Clock::now();
  double sink = 0;
  for (int k = 0; k < n; ++k) {
    Span& s = spans[k & 0xffff];
    const double b = (k % 97) * 0.03 - 1.5, h = 3.0 * 3.0 - b * b;  // across distance and the chord's half width
    if (h > 0) {
      const double w = std::sqrt(h), lo = 10 + 0.001 * (k & 1023) - w, hi = 10 + w;
      if (lo < s.hi && hi > s.lo) s.hi = static_cast<float>(std::max<double>(s.lo, lo));
    }
    sink += s.hi;
  }
  const double t = seconds_since(t0);
  if (sink == 42) std::puts("");
  return t / n;
}

}  // namespace

int main(int argc, char** argv) {
  rosmill::core::keep_freed_memory();
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  const int only = argc > 2 ? std::atoi(argv[2]) : 0;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  Box3 box;
  box.add(Vec3(0, 0, 0));
  box.add(Vec3(kSize, kSize, kHeight));
  const double clip_s = seconds_per_dexel_clip();
  std::printf("threads %d; a %g x %g x %g mm box at %g mm cells; remove = view from the setup + kernel + dexel clip\n"
              "(wall, and CPU of all threads); tri-dexel = X and Y dexels the moves cross x %.1f ns a clip\n",
              threads, kSize, kSize, kHeight, kCell, clip_s * 1e9);
  std::printf("%-26s %8s %7s %9s %7s %12s %10s %9s %8s %11s %13s\n", "case", "moves", "make s", "remove s", "CPU s",
              "removed mm3", "model MB", "B/mm3", "RSS MB", "side dexels", "tri-dexel s");
  int number = 0;
  for (const char* name : {"ball 6 finishing raster", "flat 10 roughing levels"}) {
    if (++number != only && only != 0) continue;
    const MachineProgram program = number == 1 ? ball_raster() : flat_roughing();
    auto t0 = Clock::now();
    InProcessStock stock = InProcessStock::box(box, kCell);
    const double make = seconds_since(t0);
    const double cpu0 = cpu_seconds_used();
    t0 = Clock::now();
    const RemovalReport r = stock.remove(program);
    const double remove = seconds_since(t0), cpu = cpu_seconds_used() - cpu0;
    const double side = side_dexels_crossed(program);
    std::printf("%-26s %8zu %7.3f %9.3f %7.3f %12.0f %10.1f %9.2f %8.0f %11.3g %13.1f\n", name, program.moves.size(),
                make, remove, cpu, r.removed_mm3, stock.bytes() / 1e6, stock.bytes() / (kSize * kSize * kHeight),
                peak_rss_mb(), side, side * clip_s);
  }
  return 0;
}
