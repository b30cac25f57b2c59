// rosmill plan FILE --strategy NAME [--tool ID|ball:D|flat:D|bull:D:r] [--tools FILE] [--presets FILE]
//   [--stepover ..] [--stepdown ..] [--allowance ..] [--tolerance ..] [--angle ..] [--units ..] [--json]
//   [-o toolpath.json | -o prog.ngc|.nc|.gcode [--dialect linuxcnc|grbl]] [--place REGISTRATION.json]
//   cloud files: [--orient none|ransac|lowest] [--origin corner|keep] [--voxel MM] [--outliers K]
//   [--holes bridge|skip]
// rosmill plan --list: the strategies, presets, templates and tools.
// Plans through rosmill::core::plan(request) on a mesh (STL) or a cloud (PCD/PLY). Lengths in mm. A cloud is prepared
// first (cloud/cloud_input.hpp: orientation, origin at the stock corner, filters, a density and holes report).
// NAME is a strategy, a preset or a template (config/presets.yaml); a preset takes its own tool and tolerance
// unless --tool / --tolerance are given.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "command.hpp"
#include "config_file.hpp"
#include "progress_bar.hpp"
#include "rosmill/cloud/cloud_input.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/cycle_time.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/stock.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/planner/strategy_table.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"
#include "rosmill/toolpath/toolpath_stats.hpp"
#include "rosmill/verify/tool_clearance.hpp"
#include "work_offset_option.hpp"

namespace rosmill::core::cli {
namespace {

struct Options {
  std::string file, strategy, tool = "ball:6", tools, presets, units, out, dialect = "linuxcnc", stock, machine;
  std::string setup = "+Z";
  std::string place;  // a registration JSON: the part is planned where the scan found it
  bool no_limits = false;
  double stepover = NAN, stepdown = NAN, engagement = NAN, stock_margin = PlanParams{}.stock_margin;
  ToolAxisParams tool_axis;
  double allowance = 0.0, tolerance = PlanParams{}.tolerance, angle = 0.0;
  bool json = false, list = false;
  CloudInputOptions cloud;  // --orient, --origin, --voxel, --outliers, --holes
  bool tool_given = false, tolerance_given = false;
};

// The cloud in the workpiece frame: read in its units (scaled to mm), then the shared input step.
PointCloud prepared_cloud(const Options& o, std::string& report) {
  CloudReadOptions ro;
  if (!o.units.empty()) ro.units = parse_units(o.units, "--units");
  CloudPrepReport r;
  PointCloud cloud = prepare_input_cloud(read_cloud(o.file, ro).points, o.cloud, "--", &r);
  report = format_prep_report(r);
  return cloud;
}

PresetTable preset_table(const Options& o) {
  return read_presets(o.presets.empty() ? default_config("presets.yaml") : o.presets);
}

// `rosmill plan --list`: what --strategy and --tool accept.
void list(const Options& o) {
  std::printf("strategies:\n");
  for (const StrategyEntry& s : strategies()) std::printf("  %-13s %s\n", s.name.c_str(), s.description.c_str());
  const PresetTable presets = preset_table(o);
  std::printf("presets (%s):\n", presets.source.c_str());
  for (const Preset& p : presets.presets)
    std::printf("  %-13s %s [%s, %s, %s sampling]\n", p.name.c_str(), p.description.c_str(), p.strategy.c_str(),
                p.tool.name.c_str(), sampling_name(p.sampling));
  for (const PlanTemplate& t : presets.templates) {
    std::string stages;
    for (const std::string& s : t.stages) stages += (stages.empty() ? "" : " + ") + s;
    std::printf("  %-13s %s [template: %s]\n", t.name.c_str(), t.description.c_str(), stages.c_str());
  }
  const std::string path = o.tools.empty() ? default_config("tools.yaml") : o.tools;
  std::printf("tools (%s):\n", path.c_str());
  for (const Tool& t : read_tool_table(path).tools) std::printf("  %-4d %s\n", t.id, t.name.c_str());
}

// The tools of a job, in machining order.
std::string job_tools(const Job& job) {
  std::string names;
  for (const Toolpath& tp : job) names += (names.empty() ? "" : " + ") + tp.tool.name;
  return names;
}

Tool pick_tool(const Options& o) {
  const bool numeric = !o.tool.empty() && o.tool.find(':') == std::string::npos;
  if (!numeric) return resolve_tool(o.tool, nullptr);
  const std::string path = o.tools.empty() ? default_config("tools.yaml") : o.tools;
  const ToolTable table = read_tool_table(path);
  return resolve_tool(o.tool, &table);
}

// --setup: a named setup (+Z, -X, ...) or a tool direction "x,y,z" in the part's frame.
SetupFrame setup_of(const std::string& text) {
  if (text.find(',') == std::string::npos) return named_setup(text, "--setup");
  Vec3 d;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &d.x(), &d.y(), &d.z(), &tail) != 3)
    throw Error("--setup", "expected +Z, -Z, +X, -X, +Y, -Y or a direction x,y,z, got '" + text + "'");
  return direction_setup(d, "--setup");
}

void run(const Options& o) {
  PlanParams params;
  params.tool = pick_tool(o);
  params.stepover = o.stepover;
  params.stepdown = o.stepdown;
  params.engagement_deg = o.engagement;
  params.stock_margin = o.stock_margin;
  params.allowance = o.allowance;
  params.tolerance = o.tolerance;
  params.angle_deg = o.angle;
  params.tool_axis = o.tool_axis;

  Mesh mesh;
  PointCloud cloud;
  PlanningRequest request;
  PlanInput& input = request.input;
  std::string prep_report;
  const PresetTable presets = preset_table(o);
  check_plan_name(o.strategy, &presets, "--strategy");
  const PlanTemplate* tmpl = presets.find_template(o.strategy);
  const bool preset = tmpl || presets.find(o.strategy);
  if (preset) {
    if (tmpl && o.tool_given)
      throw Error("--tool", o.strategy + " runs its presets' tools; give --tool to one of its stages");
    if (!o.tool_given) params.tool = Tool{};  // the preset's tool
    if (!o.tolerance_given) params.tolerance = NAN;  // the preset's tolerance
  }
  if (is_cloud_path(o.file)) {
    if (!o.place.empty())
      throw Error("--place", "a cloud is planned where it was scanned: --place moves an STL design only");
    input.holes = cloud_hole_policy(o.cloud, "--");
    cloud = prepared_cloud(o, prep_report);
    input.cloud = &cloud;
  } else {
    StlReadOptions ro;
    if (!o.units.empty()) ro.units = parse_units(o.units, "--units");
    mesh = read_stl(o.file, ro);
    // Where the scan found the part, tilted or not: the toolpath is then in the scan's frame (the machine's, for
    // a scan taken in machine coordinates), and no work offset has to turn it.
    if (!o.place.empty()) mesh = transformed_mesh(mesh, registered_pose(o.place), "--place " + o.place);
    input.mesh = &mesh;
  }
  // A setup turns the part over so that its tool axis becomes +Z: the toolpath is in the turned part's frame.
  const SetupFrame setup = setup_of(o.setup);
  input.setup = setup;
  Mesh stock;
  if (!o.stock.empty()) {
    if (o.strategy != "rough" && o.strategy != "adaptive")
      throw Error("--stock", "a stock mesh is used by --strategy rough and adaptive only");
    StlReadOptions ro;
    if (!o.units.empty()) ro.units = parse_units(o.units, "--units");
    try {
      stock = read_stl(o.stock, ro);
      check_stock_mesh(stock, input.mesh);
    } catch (const Error& e) {
      throw Error("--stock " + o.stock, e.what());
    }
    params.stock_mesh = &stock;
  }

  // Feeds raised for a thin engagement stop at the machine's (the one a program is checked against).
  if (const auto machine = machine_to_check(o.machine, o.no_limits)) params.max_feed = machine->max_feed;
  const auto t0 = std::chrono::steady_clock::now();
  request.strategy = o.strategy;
  request.params = params;
  request.presets = &presets;
  std::vector<PlanReport> reports;
  request.reports = &reports;
  ProgressBar bar(!o.json);
  request.progress = [&bar, &o](double fraction) {
    bar.update("plan " + o.strategy, fraction);
    return true;
  };
  const Job job = plan(request);
  bar.clear();
  const std::string tool_name = preset ? job_tools(job) : params.tool.name;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  gcode::PostOptions post = gcode::post_options_for(o.dialect);
  post_for_machine(job, o.machine, post);
  // A multi-axis toolpath's tool, tilted along its moves, against the design by a check that shares no code with
  // the planner (verify/tool_clearance.hpp): a gouge or a collision is refused before anything is written.
  std::optional<verify::ToolClearance> clearance;
  if (post.trunnion && input.mesh) {
    const Mesh turned = setup.identity() ? Mesh() : transformed_mesh(mesh, setup.placement.pose.matrix(), "--setup");
    clearance = verify::check_tool_clearance(setup.identity() ? mesh : turned, job, params.allowance);
    const double tolerance = std::isnan(params.tolerance) ? kDefaultTolerance : params.tolerance;
    if (clearance->ball_depth_mm > tolerance || clearance->body_depth_mm > tolerance + clearance->sampling_mm)
      throw Error("tool clearance", "the tilted tool goes " +
                                        std::to_string(std::max(clearance->ball_depth_mm, clearance->body_depth_mm)) +
                                        " mm into the design at " + clearance->deepest + ": no program written");
  }
  if (!o.out.empty() && gcode::is_program_path(o.out)) {
    // The same checked pipeline as `rosmill post`: limits of the machine found as `send` finds it.
    gcode::ProgramChecks checks;
    checks.machine = machine_to_check(o.machine, o.no_limits);
    // A five-axis finish approaches and leaves along its tool axes, through the space its sweep found free: the
    // stock is the part's (finishing follows roughing), whose top the rapids clear.
    if (post.trunnion && mesh.face_count() > 0) checks.limits.stock_top = mesh.bbox.max.z();
    gcode::write_program(o.out, gcode::prepare_program(job, post, checks).program);
  } else if (!o.out.empty()) {
    write_toolpath_file(o.out, job);
  }

  ToolpathStats total;
  for (const Toolpath& tp : job) {
    const ToolpathStats s = toolpath_stats(tp);
    total.moves += s.moves;
    total.cutting_length += s.cutting_length;
    total.rapid_length += s.rapid_length;
  }
  // The program this job posts, timed as the machine's trajectory planner runs it.
  const double estimated_seconds = gcode::estimate_cycle_time(job, post, machine_trajectory(o.machine)).seconds;
  if (o.json) {
    nlohmann::json j = {{"strategy", o.strategy},
                        {"toolpaths", job.size()},
                        {"tool", tool_name},
                        {"moves", total.moves},
                        {"cutting_length", total.cutting_length},
                        {"rapid_length", total.rapid_length},
                        {"estimated_seconds", estimated_seconds},
                        {"seconds", seconds}};
    if (!o.out.empty()) j["output"] = o.out;
    for (const PlanReport& r : reports)
      if (r.engagement_limit_deg > 0) {
        j["adaptive"] = {{"engagement_limit_deg", r.engagement_limit_deg},
                         {"max_engagement_deg", r.max_engagement_deg},
                         {"min_turn_radius", r.min_turn_radius},
                         {"levels", r.levels},
                         {"passes", r.passes},
                         {"corner_links", r.corner_links},
                         {"air_links", r.air_links},
                         {"short_passes", r.short_passes},
                         {"helices", r.helices},
                         {"ramps", r.ramps},
                         {"lifts", r.lifts},
                         {"left_area_mm2", r.left_area_mm2},
                         {"slot_length_mm", r.slot_length_mm},
                         {"slot_max_engagement_deg", r.slot_max_engagement_deg},
                         {"slot_feed", r.slot_feed},
                         {"uncleared", uncleared_json<nlohmann::json>(r.uncleared)}};
      }
    for (const PlanReport& r : reports)
      if (r.strategy == "five-axis" || r.strategy == "four-axis")
        j["tool_axis"] = {{"max_tilt_deg", r.max_tilt_deg},
                          {"max_axis_rate_deg_per_mm", r.max_axis_rate_deg_per_mm},
                          {"axes_turned_to_clear", r.axes_turned_to_clear},
                          {"unreachable_points", r.unreachable_points},
                          {"max_left_mm", r.max_left_mm}};
    if (clearance)
      j["tool_clearance"] = {{"ball_depth_mm", clearance->ball_depth_mm},
                             {"body_depth_mm", clearance->body_depth_mm},
                             {"sampling_mm", clearance->sampling_mm},
                             {"positions", clearance->positions}};
    const Vec3& axis = setup.tool_axis;
    j["setup"] = {{"name", setup.name}, {"tool_axis", {axis.x(), axis.y(), axis.z()}}};
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("%s", prep_report.c_str());
    std::printf("%s with %s: %zu moves, cutting %.1f mm, rapid %.1f mm, about %.0f s on the machine "
                "(planned in %.3f s)\n",
                o.strategy.c_str(), tool_name.c_str(), total.moves, total.cutting_length, total.rapid_length,
                estimated_seconds, seconds);
    // What adaptive clearing could not clear, and why (the part's own allowance not counted).
    for (const PlanReport& r : reports)
      if (r.slot_length_mm > 0) std::printf("  %s\n", slot_text(r).c_str());
    for (const PlanReport& r : reports)
      if (r.strategy == "five-axis" || r.strategy == "four-axis")
        std::printf(
            "  tool axis: up to %.1f degrees from +Z, turning up to %.2f degrees per mm; %zu cutter locations "
            "turned off lead and tilt to clear the part, %zu no axis in the cone reaches (left out); most "
            "left at a kept location %.4f mm\n",
            r.max_tilt_deg, r.max_axis_rate_deg_per_mm, r.axes_turned_to_clear, r.unreachable_points, r.max_left_mm);
    if (clearance)
      std::printf(
          "  tool against the design (checked apart from the planner, %zu positions): ball %.4f mm in, "
          "flutes, shank and holder %.4f mm (sampled within %.4f mm)\n",
          clearance->positions, clearance->ball_depth_mm, clearance->body_depth_mm, clearance->sampling_mm);
    for (const PlanReport& r : reports)
      for (const UnclearedPatch& l : r.uncleared) std::printf("  %s\n", uncleared_text(l).c_str());
  }
}

CommandRegistration reg([](CLI::App& app) {
  auto* cmd = app.add_subcommand("plan", "plan a toolpath (raster, waterline, rough, ...) on an STL or a cloud");
  auto o = std::make_shared<Options>();
  cmd->add_option("FILE", o->file, "STL, PCD or PLY file");
  cmd->add_option("--strategy", o->strategy, "strategy, preset or template name (--list names them)");
  cmd->add_flag("--list", o->list, "list the strategies, presets, templates and tools, and exit");
  cmd->add_option("--presets", o->presets, "preset table (default config/presets.yaml here, else the package's)");
  auto* tool = cmd->add_option("--tool", o->tool, "tool id in the tool table, or ball:D, flat:D, bull:D:r (mm)");
  cmd->add_option("--tools", o->tools, "tool table (default config/tools.yaml here, else the package's)");
  cmd->add_option("--stepover", o->stepover, "mm (default: the tool's)");
  cmd->add_option("--stepdown", o->stepdown, "mm (default: the tool's)");
  cmd->add_option("--engagement", o->engagement,
                  "adaptive: largest radial engagement of the cutter, degrees (default: a side cut one stepover wide)");
  cmd->add_option("--stock-margin", o->stock_margin, "box stock: the part's bounds grown by this, mm")
      ->capture_default_str();
  cmd->add_option("--allowance", o->allowance, "stock to leave, mm");
  auto* tolerance = cmd->add_option("--tolerance", o->tolerance, "chord and gouge tolerance, mm");
  cmd->add_option("--angle", o->angle, "raster direction, degrees");
  cmd->add_option("--lead", o->tool_axis.lead_deg,
                  "five-axis: the tool axis tilted from the normal towards travel, degrees (default 10 for a ball)");
  cmd->add_option("--tilt", o->tool_axis.tilt_deg, "five-axis: the tool axis tilted to the side of travel, degrees")
      ->capture_default_str();
  cmd->add_option("--cone", o->tool_axis.cone_deg, "five-axis: largest angle of the tool axis from +Z, degrees")
      ->capture_default_str();
  cmd->add_option("--axis-rate", o->tool_axis.rate_deg_per_mm,
                  "five-axis: largest change of the tool axis per mm along a pass, degrees")
      ->capture_default_str();
  cmd->add_option(
         "--setup", o->setup,
         "setup: the tool direction in the part's frame, +Z, -Z, +X, -X, +Y, -Y or x,y,z; the part is turned so "
         "that it points up, and the toolpath is in the turned part's frame")
      ->capture_default_str();
  cmd->add_option("--place", o->place,
                  "the JSON of rosmill register --json: plan the part where the scan found it (tilted or not); the "
                  "toolpath is in the scan's frame. An ambiguous registration is refused");
  cmd->add_option("--stock", o->stock,
                  "rough: stock STL (closed, containing the part; same --units) instead of the box");
  cmd->add_option("--units", o->units, "units of the file: mm, inch, m (STL default mm, clouds m)");
  cmd->add_flag("--json", o->json, "print one JSON object");
  cmd->add_option("-o,--out", o->out, "write toolpath.json, or a G-code program when it ends in .ngc, .nc or .gcode");
  cmd->add_option("--dialect", o->dialect, "G-code dialect for -o prog.ngc: linuxcnc or grbl")->capture_default_str();
  cmd->add_option(
      "--machine", o->machine,
      "-o prog.ngc: machine limits the program must keep (default config/machine.yaml here, else the package's)");
  cmd->add_flag("--no-limits", o->no_limits, "-o prog.ngc: write the program without checking the machine's limits");
  cmd->add_option("--orient", o->cloud.orient,
                  "cloud: none, ransac (fit the base plane) or lowest (fit the lowest points)");
  cmd->add_option("--origin", o->cloud.origin, "cloud: corner (program origin at the stock corner) or keep");
  cmd->add_option("--voxel", o->cloud.voxel, "cloud: voxel downsampling leaf, mm (0: off)");
  cmd->add_option("--outliers", o->cloud.outliers, "cloud: statistical outlier removal over K neighbours (0: off)");
  cmd->add_option("--holes", o->cloud.holes, "cloud: bridge holes at the highest neighbour, or skip them");
  cmd->callback([o, cmd, tool, tolerance] {
    if (o->list) return list(*o);
    if (o->file.empty()) throw Error("plan", "FILE is required (or --list)");
    if (o->strategy.empty()) throw Error("--strategy", "is required (rosmill plan --list names the strategies)");
    // NaN means "the default" inside PlanParams: a NaN typed on the command line must not pass as that.
    for (const char* name : {"--stepover", "--stepdown", "--engagement", "--stock-margin", "--allowance", "--tolerance",
                             "--angle", "--lead", "--tilt", "--cone", "--axis-rate"})
      if (cmd->count(name) && !std::isfinite(cmd->get_option(name)->as<double>()))
        throw Error(name, "must be a finite number");
    o->tool_given = tool->count() > 0;
    o->tolerance_given = tolerance->count() > 0;
    run(*o);
  });
});

}  // namespace
}  // namespace rosmill::core::cli
