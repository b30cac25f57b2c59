#include "rosmill/job/run_job.hpp"

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/stock/design_height.hpp"
#include "rosmill/stock/in_process_stock.hpp"
#include "rosmill/toolpath/toolpath_stats.hpp"
#include "rosmill/verify/verify.hpp"

namespace rosmill::core::job {
namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The part, or a cast stock: an STL in the job's units or a primitive of the STL slicing paper (millimetres).
Mesh read_mesh(const std::string& path, Units units) {
  const std::string primitive = "primitive:";
  if (path.rfind(primitive, 0) == 0) return make_primitive(path.substr(primitive.size()));
  StlReadOptions o;
  o.units = units;
  return read_stl(path, o);
}

stock::InProcessStock raw_stock(const JobSpec& job, const Mesh& part, const Mesh* stock_mesh) {
  const std::string where = job.source + " stock";
  switch (job.stock.kind) {
    case StockSpec::Kind::Box: {
      // The box the roughing strategies assume: the part's bounds grown by the margin sideways and up.
      Box3 b = part.bbox;
      b.min.head<2>() -= Vec2::Constant(job.stock.margin);
      b.max += Vec3::Constant(job.stock.margin);
      return stock::InProcessStock::box(b, job.resolution, stock::kMaxGridCells, where);
    }
    case StockSpec::Kind::Mesh:
      return stock::InProcessStock::from_mesh(*stock_mesh, job.resolution, stock::kMaxGridCells, where);
    case StockSpec::Kind::Cloud: {
      CloudReadOptions o;
      o.units = job.stock.units;
      return stock::InProcessStock::from_cloud(read_cloud(job.stock.file, o), job.stock.table_z, job.resolution, 3,
                                               stock::kMaxGridCells, where);
    }
  }
  throw Error(where, "unknown kind");
}

std::string program_path(const std::string& dir, size_t index, const std::string& name) {
  char prefix[24];
  std::snprintf(prefix, sizeof prefix, "%02zu_", index + 1);
  std::string safe;
  for (char c : name) safe += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  return (std::filesystem::path(dir) / (prefix + safe + ".ngc")).string();
}

// The stock seen from a setup and the design's top over the same cells.
struct PartView {
  stock::HeightField stock;
  std::vector<float> design;
  Mesh part;  // in the setup's frame
  // A cell of the part: the design stands there above the floor, and the stock has material.
  bool on_part(size_t c) const {
    return design[c] > stock.bottom + 1e-6 && stock.top[c] != stock::kNoMaterial;
  }
};

PartView part_view(const stock::InProcessStock& stock, const Mesh& part, const SetupFrame& setup) {
  PartView v{stock.view(setup), {}, placed(part, setup.placement)};
  v.design = stock::design_heights(v.part, v.stock.grid, v.stock.bottom);
  return v;
}

// The least and the most material the stock leaves on the part, seen from the operation's setup: the stock's top
// minus the design's, over the cells the design covers (above the floor it stands on). Negative: a gouge.
std::pair<double, double> material_left(const PartView& v) {
  double lo = INFINITY, hi = -INFINITY;
  for (size_t c = 0; c < v.design.size(); ++c) {
    if (!v.on_part(c)) continue;
    const double left = double(v.stock.top[c]) - v.design[c];
    lo = std::min(lo, left);
    hi = std::max(hi, left);
  }
  return {lo, hi};
}

// The deepest cut below the design by the operation's program and the toolpath move that made it (0: none), from
// the verifier, which sweeps the program over a fresh height field of the part in the setup's frame, apart from
// the stock the operations carry: a second opinion on the gouge that the stock's material left gives.
std::pair<double, uint32_t> verified_gouge(const PartView& v, const stock::MachineProgram& program, double cell) {
  if (program.moves.empty()) return {0.0, 0};
  verify::VerifyOptions o;
  o.resolution = cell;
  const verify::DeviationReport d = verify::verify_program(v.part, program, verify::StockSpec{}, o).report;
  return {d.gouged ? d.max_gouge_mm : 0.0, d.gouged ? d.gouge_source : 0};
}

// What planning is told of the stock: its top from the operation's setup and, for a rest operation, the cells of
// the part where more than the allowance and the threshold is left. Returns the number of rest cells.
size_t material_for(const PartView& v, const OperationSpec& op, MaterialTop& m) {
  const stock::GridSpec& g = v.stock.grid;
  m.x0 = g.x0, m.y0 = g.y0, m.cell = g.cell, m.nx = g.nx, m.ny = g.ny;
  m.top = v.stock.top;
  m.rest.clear();
  if (!op.rest) return 0;
  // The cells where the design stands and the stock left more than the allowance and the threshold over the
  // design's highest within the cell (its centre height would make every steep flank rest material).
  const std::vector<float> high = stock::design_highest_in_cells(v.part, g, v.stock.bottom, v.design);
  m.rest.assign(m.top.size(), 0);
  size_t n = 0;
  for (size_t c = 0; c < m.top.size(); ++c)
    n += m.rest[c] = v.on_part(c) && m.top[c] - high[c] > op.allowance + op.rest_threshold;
  return n;
}

// The job's programs: one per run of operations in the same setup (the part stays clamped; the tools change with
// M6 T between them), or one per operation on request. Every program is prepared and checked before any is
// written, so a job that fails a check leaves no program behind.
void write_programs(const JobSpec& job, const std::vector<Job>& planned, const JobOptions& options,
                    JobReport& report) {
  std::vector<std::pair<std::string, gcode::Program>> programs;
  // Every rapid was swept through the in-process stock, which knows the stock's top under it: the links low over
  // the material need not clear the whole stock's top.
  gcode::ProgramChecks checks = options.checks;
  checks.limits.rapids_checked_by_stock = true;
  for (const auto& [first, end] : program_groups(job, planned.size(), options.per_operation)) {
    Job toolpaths;
    for (size_t k = first; k < end; ++k) toolpaths.insert(toolpaths.end(), planned[k].begin(), planned[k].end());
    const std::string name =
        options.per_operation ? job.operations[first].name : "setup " + job.operations[first].setup;
    const std::string path = program_path(options.out_dir, programs.size(), name);
    gcode::PostOptions post = gcode::post_options_for(options.dialect);
    post.title = "rosmill job " + job.source + ": " + name;
    post.work_offset = options.work_offset;
    programs.emplace_back(path, gcode::prepare_program(toolpaths, post, checks).program);
    for (size_t k = first; k < end; ++k) report.operations[k].program = path;
  }
  std::filesystem::create_directories(options.out_dir);
  for (const auto& [path, program] : programs) gcode::write_program(path, program);
}

}  // namespace

std::vector<std::pair<size_t, size_t>> program_groups(const JobSpec& job, size_t operations, bool per_operation) {
  std::vector<std::pair<size_t, size_t>> groups;
  for (size_t first = 0; first < operations;) {
    size_t end = first + 1;
    while (!per_operation && end < operations && job.operations[end].setup == job.operations[first].setup) ++end;
    groups.emplace_back(first, end);
    first = end;
  }
  return groups;
}

JobReport run_job(const JobSpec& job, const JobOptions& options) {
  const Mesh part = options.part ? *options.part : read_mesh(job.part, job.units);
  std::optional<Mesh> stock_mesh;
  if (job.stock.kind == StockSpec::Kind::Mesh) stock_mesh = read_mesh(job.stock.file, job.units);
  stock::InProcessStock stock = raw_stock(job, part, stock_mesh ? &*stock_mesh : nullptr);
  JobReport report;
  report.stock_mm3 = stock.volume();
  double feed_mm = 0, air_mm = 0;
  std::vector<Job> planned;  // each operation's toolpaths, for the programs
  const auto go_on = [&](size_t k, double fraction) { return !options.progress || options.progress(k, fraction); };
  for (size_t k = 0; k < job.operations.size(); ++k) {
    if (!go_on(k, 0.0)) {
      report.cancelled = true;
      break;
    }
    const OperationSpec& op = job.operations[k];
    const std::string where = job.source + ":" + std::to_string(op.line) + " operations[" + std::to_string(k) + "]";
    OperationReport r;
    r.name = op.name;
    r.strategy = op.strategy;
    r.setup = op.setup;
    r.rest = op.rest;
    PlanningRequest request;
    request.input.mesh = &part;
    request.input.setup = named_setup(op.setup, where + ".setup");
    request.strategy = op.strategy;
    request.presets = options.presets;
    check_plan_name(op.strategy, options.presets, where + ".strategy");
    try {
      request.params.tool = resolve_tool(op.tool, options.tools);
    } catch (const Error& e) {
      throw Error(where + ".tool", e.what());
    }
    request.params.stepover = op.stepover;
    request.params.stepdown = op.stepdown;
    request.params.allowance = op.allowance;
    if (!std::isnan(op.tolerance)) request.params.tolerance = op.tolerance;
    if (job.stock.kind == StockSpec::Kind::Box) request.params.stock_margin = job.stock.margin;
    if (stock_mesh) request.params.stock_mesh = &*stock_mesh;
    // Every operation plans on the material the ones before left (and the raw stock's real shape).
    MaterialTop material;
    const size_t rest_cells = material_for(part_view(stock, part, request.input.setup), op, material);
    if (options.plan_on_stock) request.params.material = &material;
    request.params.link_clearance = options.link_clearance;
    r.tool = request.params.tool.name;
    // Planning takes the first 90 % of an operation's progress, the removal from the stock the rest.
    bool stopped = false;
    request.progress = [&](double f) { return !(stopped = !go_on(k, 0.9 * f)); };
    auto t0 = std::chrono::steady_clock::now();
    Job toolpaths;
    try {
      // A rest operation with no rest material left has nothing to cut.
      if (!op.rest || rest_cells > 0 || !options.plan_on_stock) toolpaths = plan(request);
    } catch (const Error&) {
      if (!stopped) throw;
      report.cancelled = true;
      break;
    }
    r.plan_seconds = since(t0);
    const stock::MachineProgram program = stock::program_from_job(toolpaths);
    const stock::RemovalReport removal = stock.remove(program, request.input.setup);
    // A rapid through material is a crash: no program of this job is written.
    if (removal.collided())
      throw Error(where, "a rapid runs into the stock at toolpath move " + std::to_string(removal.first_rapid_source) +
                             " (" + std::to_string(removal.rapid_cut_cells) +
                             " cells): the stock stands higher than this operation's safe height; give the "
                             "stock's real shape or raise the clearance");
    r.moves = program.moves.size();
    r.removed_mm3 = removal.removed_mm3;
    r.air_feed_mm = removal.air_feed_mm;
    r.air_cut_share = removal.air_cut_share();
    r.collision_line = removal.first_rapid_source;
    r.remove_seconds = removal.seconds;
    const PartView after = part_view(stock, part, request.input.setup);
    std::tie(r.min_left_mm, r.max_left_mm) = material_left(after);
    std::tie(r.gouge_mm, r.gouge_move) = verified_gouge(after, program, job.resolution);
    r.rest_cells = rest_cells;
    for (const Toolpath& tp : toolpaths) {
      const ToolpathStats s = toolpath_stats(tp, job.rapid_feed, options.max_acceleration);
      r.cutting_mm += s.cutting_length;
      r.rapid_mm += s.rapid_length;
      r.time_s += s.estimated_seconds;
    }
    planned.push_back(toolpaths);
    feed_mm += removal.feed_mm;
    air_mm += removal.air_feed_mm;
    report.removed_mm3 += r.removed_mm3;
    report.time_s += r.time_s;
    report.min_left_mm = std::min(report.min_left_mm, r.min_left_mm);
    report.gouge_mm = std::max(report.gouge_mm, r.gouge_mm);
    report.operations.push_back(r);
    if (options.operation_done)
      options.operation_done({k, report.operations.back(), planned.back(), request.input.setup, stock, part});
    if (!go_on(k, 1.0) && k + 1 < job.operations.size()) {
      report.cancelled = true;
      break;
    }
  }
  if (!options.out_dir.empty()) write_programs(job, planned, options, report);
  report.left_mm3 = stock.volume();
  if (!report.operations.empty()) report.max_left_mm = report.operations.back().max_left_mm;
  report.air_cut_share = feed_mm > 0 ? air_mm / feed_mm : 0.0;
  report.stock_bytes = stock.bytes();
  return report;
}

nlohmann::json to_json(const JobReport& report) {
  nlohmann::json ops = nlohmann::json::array();
  for (const OperationReport& r : report.operations) {
    nlohmann::json o = {{"name", r.name},           {"strategy", r.strategy},
                        {"tool", r.tool},           {"setup", r.setup},
                        {"moves", r.moves},         {"cutting_mm", r.cutting_mm},
                        {"rapid_mm", r.rapid_mm},   {"air_feed_mm", r.air_feed_mm},
                        {"air_cut_share", r.air_cut_share}, {"removed_mm3", r.removed_mm3},
                        {"time_s", r.time_s},       {"plan_seconds", r.plan_seconds},
                        {"rapid_collision_line", r.collision_line},
                        {"min_left_mm", r.min_left_mm},     {"max_left_mm", r.max_left_mm},
                        {"gouge_mm", r.gouge_mm},           {"gouge_move", r.gouge_move},
                        {"rest", r.rest},                   {"rest_cells", r.rest_cells}};
    if (!r.program.empty()) o["program"] = r.program;
    ops.push_back(o);
  }
  return {{"operations", ops},
          {"stock_mm3", report.stock_mm3},
          {"left_mm3", report.left_mm3},
          {"removed_mm3", report.removed_mm3},
          {"air_cut_share", report.air_cut_share},
          {"time_s", report.time_s},
          {"min_left_mm", report.min_left_mm},
          {"max_left_mm", report.max_left_mm},
          {"gouge_mm", report.gouge_mm},
          {"stock_bytes", report.stock_bytes},
          {"cancelled", report.cancelled}};
}

}  // namespace rosmill::core::job
