// rosmill plan FILE --strategy NAME [--tool ID|ball:D|flat:D|bull:D:r] [--tools FILE] [--stepover ..]
//   [--stepdown ..] [--allowance ..] [--tolerance ..] [--angle ..] [--units ..] [--json]
//   [-o toolpath.json | -o prog.ngc|.nc|.gcode [--dialect linuxcnc|grbl]]
// Plans a toolpath through rosmill::plan() on a mesh (STL) or a cloud (PCD/PLY). Lengths in mm.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "command.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/strategy.hpp"
#include "rosmill/plan/toolpath_io.hpp"

namespace rosmill::cli {
namespace {

struct Options {
  std::string file, strategy, tool = "ball:6", tools, units, out, dialect = "linuxcnc";
  double stepover = NAN, stepdown = NAN, allowance = 0.0, tolerance = 0.001, angle = 0.0;
  bool json = false;
};

Tool pick_tool(const Options& o) {
  const bool numeric = !o.tool.empty() && o.tool.find(':') == std::string::npos;
  if (!numeric) return resolve_tool(o.tool, nullptr);
  const std::string path = o.tools.empty() ? "config/tools.yaml" : o.tools;
  const ToolTable table = read_tool_table(path);
  return resolve_tool(o.tool, &table);
}

void run(const Options& o) {
  PlanParams params;
  params.tool = pick_tool(o);
  params.stepover = o.stepover;
  params.stepdown = o.stepdown;
  params.allowance = o.allowance;
  params.tolerance = o.tolerance;
  params.angle_deg = o.angle;

  Mesh mesh;
  PointCloud cloud;
  PlanInput input;
  if (is_cloud_path(o.file)) {
    CloudReadOptions ro;
    if (!o.units.empty()) ro.units = parse_units(o.units, "--units");
    cloud = read_cloud(o.file, ro);
    input.cloud = &cloud;
  } else {
    StlReadOptions ro;
    if (!o.units.empty()) ro.units = parse_units(o.units, "--units");
    mesh = read_stl(o.file, ro);
    input.mesh = &mesh;
  }

  const auto t0 = std::chrono::steady_clock::now();
  const Job job = plan(o.strategy, input, params);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!o.out.empty() && gcode::is_program_path(o.out)) {
    gcode::write_program(o.out, gcode::post(job, gcode::post_options_for(o.dialect)));
  } else if (!o.out.empty()) {
    write_toolpath_file(o.out, job);
  }

  ToolpathStats total;
  for (const Toolpath& tp : job) {
    const ToolpathStats s = toolpath_stats(tp);
    total.moves += s.moves;
    total.cutting_length += s.cutting_length;
    total.rapid_length += s.rapid_length;
    total.estimated_seconds += s.estimated_seconds;
  }
  if (o.json) {
    nlohmann::json j = {{"strategy", o.strategy},
                        {"toolpaths", job.size()},
                        {"tool", params.tool.name},
                        {"moves", total.moves},
                        {"cutting_length", total.cutting_length},
                        {"rapid_length", total.rapid_length},
                        {"estimated_seconds", total.estimated_seconds},
                        {"seconds", seconds}};
    if (!o.out.empty()) j["output"] = o.out;
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("%s with %s: %zu moves, cutting %.1f mm, rapid %.1f mm, about %.0f s at the tool's feeds "
                "(planned in %.3f s)\n",
                o.strategy.c_str(), params.tool.name.c_str(), total.moves, total.cutting_length, total.rapid_length,
                total.estimated_seconds, seconds);
  }
}

CommandRegistration reg([](CLI::App& app) {
  auto* cmd = app.add_subcommand("plan", "plan a toolpath (raster, waterline, rough, ...) on an STL or a cloud");
  auto o = std::make_shared<Options>();
  cmd->add_option("FILE", o->file, "STL, PCD or PLY file")->required();
  cmd->add_option("--strategy", o->strategy, "strategy name")->required();
  cmd->add_option("--tool", o->tool, "tool id in the tool table, or ball:D, flat:D, bull:D:r (mm)");
  cmd->add_option("--tools", o->tools, "tool table (default config/tools.yaml)");
  cmd->add_option("--stepover", o->stepover, "mm (default: the tool's)");
  cmd->add_option("--stepdown", o->stepdown, "mm (default: the tool's)");
  cmd->add_option("--allowance", o->allowance, "stock to leave, mm");
  cmd->add_option("--tolerance", o->tolerance, "chord and gouge tolerance, mm");
  cmd->add_option("--angle", o->angle, "raster direction, degrees");
  cmd->add_option("--units", o->units, "units of the file: mm, inch, m (STL default mm, clouds m)");
  cmd->add_flag("--json", o->json, "print one JSON object");
  cmd->add_option("-o,--out", o->out, "write toolpath.json, or a G-code program when it ends in .ngc, .nc or .gcode");
  cmd->add_option("--dialect", o->dialect, "G-code dialect for -o prog.ngc: linuxcnc or grbl")->capture_default_str();
  cmd->callback([o] { run(*o); });
});

}  // namespace
}  // namespace rosmill::cli
