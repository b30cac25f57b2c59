// The first load as a user meets it: the whole process `rosmill info FILE` beside `admesh FILE` (Debian's admesh:
// read, exact weld, connectivity and the statistics it prints), wall clock from spawn to exit, the file in the page
// cache (a first run of each is not counted). Files: a generated 2,012,000-triangle binary wavy solid (100.6 MB,
// written once into the build folder), demo2 (ASCII, unpacked there), counter.unitsmm.STL (binary, 4.2 MB), the
// small real parts of the shared data (88 KB to 1.1 MB), and the start-up alone: the 12-triangle cube. Minor page
// faults are the child's own (getrusage of the waited process): each is a fresh page the process touched.
//
// Two ways of running, because they differ on a virtual machine: back to back (best and worst of N), and single
// runs each after a pause. A fresh page costs little when the host still backs it, and about 2 ms per MB when the
// guest has handed it back (virtio-balloon free page reporting returns free 2 MB blocks to the host seconds after
// they are freed), so a run that follows another one's free reuses warm memory and a run after a pause does not.
// Then, in this process, where a load's time goes on each file: reading and welding, the full Mesh and its report
// (what `info` did before), and the report straight from the welded triangles (what it does now).
// Usage: bench_load_vs_admesh [runs] [ROSMILL] [pause_s]   (ROSMILL: another build of the tool, e.g. an older one, "" for
// this build's;
// pause_s: seconds before each run of the paused table, default 5, 0 leaves it out)
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/testing/unpacked.hpp"
#include "rosmill/testing/wavy_solid.hpp"

extern char** environ;

using namespace rosmill::core;
namespace fs = std::filesystem;

namespace {

struct Run {
  double seconds = 1e300;
  long minor_faults = 0;
  long max_rss_kb = 0;
  int status = 0;
};

// One child with its output discarded: wall seconds, its page faults and peak memory.
Run run_once(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t io;
  posix_spawn_file_actions_init(&io);
  posix_spawn_file_actions_addopen(&io, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&io, 2, "/dev/null", O_WRONLY, 0);
  Run r;
  pid_t pid = 0;
  const auto t0 = std::chrono::steady_clock::now();
  if (posix_spawnp(&pid, args[0], &io, nullptr, args.data(), environ) != 0) {
    posix_spawn_file_actions_destroy(&io);
    r.status = -1;
    return r;
  }
  struct rusage ru {};
  wait4(pid, &r.status, 0, &ru);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  posix_spawn_file_actions_destroy(&io);
  r.minor_faults = ru.ru_minflt;
  r.max_rss_kb = ru.ru_maxrss;
  return r;
}

struct Spread {
  Run best;
  double worst = 0.0;
};

// Back to back, after one run that brings the file and the program into the page cache.
Spread best_of(const std::vector<std::string>& argv, int runs) {
  run_once(argv);
  Spread s;
  for (int k = 0; k < runs; ++k) {
    const Run r = run_once(argv);
    if (r.status != 0) return {r, 0.0};
    if (r.seconds < s.best.seconds) s.best = r;
    s.worst = std::max(s.worst, r.seconds);
  }
  return s;
}

// One run after a pause in which nothing runs.
Run after_pause(const std::vector<std::string>& argv, double pause_s) {
  std::this_thread::sleep_for(std::chrono::duration<double>(pause_s));
  return run_once(argv);
}

// Best wall seconds of `runs` calls of work().
template <class Work>
double best_seconds(int runs, const Work& work) {
  double best = 1e300;
  for (int k = 0; k < runs; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    work();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

// The phases of one load in this process, best of `runs` each.
void print_phases(const char* name, const std::string& path, int runs) {
  IndexedTriangles t;
  const double read = best_seconds(runs, [&] { t = read_stl_triangles(path); });
  Mesh mesh;
  const double build = best_seconds(runs, [&] { mesh = mesh_from_indexed(t); });
  MeshReport r;
  const double full = best_seconds(runs, [&] { r = report(mesh); });
  const double quick = best_seconds(runs, [&] { r = report(t); });
  std::printf("%-26s %12.4f %12.4f %12.4f %12.4f\n", name, read, build, full, quick);
}

size_t shared_libraries(const std::string& exe) {
  const std::string cmd = "ldd '" + exe + "' 2>/dev/null";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return 0;
  size_t n = 0;
  char line[1024];
  while (std::fgets(line, sizeof line, p)) n += std::string(line).find("=>") != std::string::npos;
  pclose(p);
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const std::string cli = argc > 2 && argv[2][0] ? argv[2] : ROSMILL_CLI;
  const double pause_s = argc > 3 ? std::atof(argv[3]) : 5.0;
  const fs::path data = fs::path(ROSMILL_CLI).parent_path().parent_path() / "bench-data";
  fs::create_directories(data);
  const fs::path wavy = data / "wavy-2M.stl", cube = data / "cube.stl";
  if (!fs::exists(wavy)) write_stl(wavy.string(), build_mesh(wavy_solid_corners()), false);
  if (!fs::exists(cube)) write_stl(cube.string(), make_primitive("cube"), false);
  const std::string shared = std::string(ROSMILL_SHARED_DATA) + "/stl/";
  const std::string demo2 = fs::exists(data / "demo2.stl") ? (data / "demo2.stl").string()
                                                            : unpacked(shared + "demo2.stl.gz", data.string());
  struct File {
    const char* name;
    std::string path;
    double goal;  // admesh seconds / rosmill seconds at least
  };
  const File files[] = {{"wavy-2M (binary)", wavy.string(), 5.0},
                        {"demo2 (ASCII)", demo2, 5.0},
                        {"counter.unitsmm (binary)", shared + "counter.unitsmm.STL", 1.0},
                        {"wheel_in_box (binary)", shared + "wheel_in_box.stl", 1.0},
                        {"mount_rush (binary)", shared + "mount_rush.stl", 1.0},
                        {"pycam-textbox (ASCII)", shared + "pycam-textbox.stl", 1.0},
                        {"ktoolcav (binary)", shared + "ktoolcav.stl", 1.0},
                        {"featuretype (binary)", shared + "featuretype.STL", 1.0},
                        {"failedinpycam (ASCII)", shared + "failedinpycam.stl", 1.0},
                        {"cube, start-up (binary)", cube.string(), 0.0}};
  std::printf("rosmill %s: %zu shared libraries (ldd)\n", cli.c_str(), shared_libraries(cli));
  std::printf("whole process, wall clock, back to back: best and worst of %d; x = admesh best / rosmill best, "
              "worst x = admesh worst / rosmill worst; faults = minor page faults of the child (best run)\n",
              runs);
  std::printf("%-26s %7s %9s %9s %7s %7s %9s %9s %7s %7s %7s %5s\n", "file", "MB", "rosmill s", "worst s",
              "faults", "RSS MB", "admesh s", "worst s", "faults", "x", "worst x", "goal");
  for (const File& f : files) {
    if (f.path.empty() || !fs::exists(f.path)) {
      std::printf("%-26s skipped: not found\n", f.name);
      continue;
    }
    const double mb = double(fs::file_size(f.path)) / 1e6;
    const Spread r = best_of({cli, "info", f.path}, runs);
    const Spread a = best_of({"admesh", f.path}, runs);
    if (r.best.status != 0) std::printf("%-26s rosmill failed (status %d)\n", f.name, r.best.status);
    if (a.best.status != 0)
      std::printf("%-26s admesh failed or missing (status %d; apt-get install admesh)\n", f.name, a.best.status);
    if (r.best.status != 0 || a.best.status != 0) continue;
    const double x = a.best.seconds / r.best.seconds, worst_x = a.worst / r.worst;
    std::printf("%-26s %7.2f %9.4f %9.4f %7ld %7.1f %9.4f %9.4f %7ld %7.2f %7.2f %5s\n", f.name, mb,
                r.best.seconds, r.worst, r.best.minor_faults, r.best.max_rss_kb / 1024.0, a.best.seconds, a.worst,
                a.best.minor_faults, x, worst_x,
                f.goal == 0 ? "-" : std::min(x, worst_x) >= f.goal ? "met" : "MISS");
    std::fflush(stdout);
  }
  if (pause_s > 0) {
    std::printf("\nsingle runs, each after %.0f s of pause (its fresh memory no longer warm on the host), "
                "rosmill and admesh in turn\n", pause_s);
    std::printf("%-26s %9s %9s %7s %7s\n", "file", "rosmill s", "admesh s", "x", "goal");
    for (const File& f : files) {
      if (f.goal < 5.0 || !fs::exists(f.path)) continue;
      for (int k = 0; k < runs; ++k) {
        const Run r = after_pause({cli, "info", f.path}, pause_s);
        const Run a = after_pause({"admesh", f.path}, pause_s);
        if (r.status != 0 || a.status != 0) continue;
        const double x = a.seconds / r.seconds;
        std::printf("%-26s %9.4f %9.4f %7.2f %5s\n", f.name, r.seconds, a.seconds, x, x >= f.goal ? "met" : "MISS");
        std::fflush(stdout);
      }
    }
  }
  std::printf("\nin-process phases, seconds, best of %d\n", runs);
  std::printf("%-26s %12s %12s %12s %12s\n", "file", "read+weld", "full Mesh", "its report", "quick report");
  for (const File& f : files)
    if (!f.path.empty() && fs::exists(f.path)) print_phases(f.name, f.path, runs);
  return 0;
}
