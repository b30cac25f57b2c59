// rosmill dropcutter FILE --tool ball:D|flat:D|bull:D:r --spacing S [--threads N] [--json] [--out FILE.xyz]
// Drops the cutter on a grid over the model (numbers in the file's own units) and reports the rate.
#include <chrono>
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "command.hpp"
#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/plan/drop_grid.hpp"
#include "rosmill/plan/mesh_surface.hpp"

namespace rosmill::core::cli {
namespace {

struct Options {
  std::string file, tool, out;
  double spacing = 0;
  int threads = 0;
  bool json = false;
};

void write_xyz(const std::string& path, const std::vector<Vec3>& points) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) throw Error(path, "cannot open for writing");
  for (const Vec3& p : points)
    if (std::fprintf(f.get(), "%.10g %.10g %.10g\n", p.x(), p.y(), p.z()) < 0) throw Error(path, "write failed");
}

void run(const Options& o) {
  const Cutter cutter = parse_cutter_spec(o.tool, "--tool");
  if (o.threads < 0) throw Error("--threads", "must be >= 1");
  const ThreadLimit limit(o.threads);  // 0: every core
  // Units mm: the file's numbers are kept as they are, so D and S are in the file's units.
  const Mesh mesh = read_stl(o.file);
  const DropGrid grid = grid_over(mesh.bbox, cutter.radius(), o.spacing);

  const auto t0 = std::chrono::steady_clock::now();
  const MeshSurface surface(mesh);
  const std::vector<Vec3> points = drop_grid(surface, cutter, grid, mesh.bbox.min.z());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (!o.out.empty()) write_xyz(o.out, points);
  const double rate = seconds > 0 ? double(points.size()) / seconds : 0.0;
  if (o.json) {
    nlohmann::json j = {{"points", points.size()}, {"seconds", seconds}, {"points_per_second", rate}};
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("%zu points (%zu x %zu), %zu triangles, %.3f s, %.0f points/s\n", points.size(), grid.nx, grid.ny,
                mesh.face_count(), seconds, rate);
  }
}

CommandRegistration reg([](CLI::App& app) {
  auto* cmd = app.add_subcommand("dropcutter", "drop a cutter on a grid over an STL model (file units)");
  auto o = std::make_shared<Options>();
  cmd->add_option("FILE", o->file, "STL file")->required();
  cmd->add_option("--tool", o->tool, "ball:D, flat:D or bull:D:r (file units)")->required();
  cmd->add_option("--spacing", o->spacing, "grid step (file units)")->required();
  cmd->add_option("--threads", o->threads, "threads (default: all cores)");
  cmd->add_flag("--json", o->json, "print {points, seconds, points_per_second}");
  cmd->add_option("--out", o->out, "write x y z per line");
  cmd->callback([o] { run(*o); });
});

}  // namespace
}  // namespace rosmill::core::cli
