// The first load as a user meets it: the whole process `rosmill info FILE` beside `admesh FILE` (Debian's admesh:
// read, exact weld, connectivity and the statistics it prints), wall clock from spawn to exit, best of N, the file
// in the page cache (a first run of each is not counted). Files: a generated 2,012,000-triangle binary wavy solid
// (100.6 MB, written once into the build folder), demo2 (ASCII, unpacked there) and counter.unitsmm.STL (binary,
// 4.2 MB); and the start-up alone: `rosmill info` on the 12-triangle cube. Minor page faults are the child's own
// (getrusage of the waited process): each is a fresh page the process touched. Then, in this process, where a
// load's time goes on each file: reading and welding, the full Mesh and its report (what `info` did before), and
// the report straight from the welded triangles (what it does now).
// Usage: bench_load_vs_admesh [runs] [ROSMILL]   (another build of the tool, e.g. an older one, to compare)
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

Run best_of(const std::vector<std::string>& argv, int runs) {
  run_once(argv);  // the file and the program into the page cache
  Run best;
  for (int k = 0; k < runs; ++k) {
    const Run r = run_once(argv);
    if (r.status != 0) return r;
    if (r.seconds < best.seconds) best = r;
  }
  return best;
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
  const std::string cli = argc > 2 ? argv[2] : ROSMILL_CLI;
  const fs::path data = fs::path(ROSMILL_CLI).parent_path().parent_path() / "bench-data";
  fs::create_directories(data);
  const fs::path wavy = data / "wavy-2M.stl", cube = data / "cube.stl";
  if (!fs::exists(wavy)) write_stl(wavy.string(), build_mesh(wavy_solid_corners()), false);
  if (!fs::exists(cube)) write_stl(cube.string(), make_primitive("cube"), false);
  const std::string demo2 = fs::exists(data / "demo2.stl")
                                ? (data / "demo2.stl").string()
                                : unpacked(std::string(ROSMILL_SHARED_DATA) + "/stl/demo2.stl.gz", data.string());
  struct File {
    const char* name;
    std::string path;
    double goal;  // admesh seconds / rosmill seconds at least
  };
  const File files[] = {{"wavy-2M (binary)", wavy.string(), 4.0},
                        {"demo2 (ASCII)", demo2, 4.0},
                        {"counter.unitsmm (binary)",
                         std::string(ROSMILL_SHARED_DATA) + "/stl/counter.unitsmm.STL", 1.0},
                        {"cube, start-up (binary)", cube.string(), 0.0}};
  std::printf("rosmill %s: %zu shared libraries (ldd)\n", cli.c_str(), shared_libraries(cli));
  std::printf("whole process, wall clock, best of %d; faults = minor page faults of the child\n", runs);
  std::printf("%-26s %8s %9s %9s %9s %9s %9s %7s %5s\n", "file", "MB", "rosmill s", "faults", "RSS MB", "admesh s",
              "faults", "x", "goal");
  for (const File& f : files) {
    if (f.path.empty() || !fs::exists(f.path)) {
      std::printf("%-26s skipped: not found\n", f.name);
      continue;
    }
    const double mb = double(fs::file_size(f.path)) / 1e6;
    const Run r = best_of({cli, "info", f.path}, runs);
    const Run a = best_of({"admesh", f.path}, runs);
    if (r.status != 0) std::printf("%-26s rosmill failed (status %d)\n", f.name, r.status);
    if (a.status != 0) std::printf("%-26s admesh failed or missing (status %d; apt-get install admesh)\n", f.name,
                                   a.status);
    if (r.status != 0 || a.status != 0) continue;
    const double x = a.seconds / r.seconds;
    std::printf("%-26s %8.1f %9.4f %9ld %9.1f %9.4f %9ld %7.2f %5s\n", f.name, mb, r.seconds, r.minor_faults,
                r.max_rss_kb / 1024.0, a.seconds, a.minor_faults, x,
                f.goal == 0 ? "-" : x >= f.goal ? "met" : "MISS");
    std::fflush(stdout);
  }
  std::printf("\nin-process phases, seconds, best of %d\n", runs);
  std::printf("%-26s %12s %12s %12s %12s\n", "file", "read+weld", "full Mesh", "its report", "quick report");
  for (const File& f : files)
    if (!f.path.empty() && fs::exists(f.path)) print_phases(f.name, f.path, runs);
  return 0;
}
