#include "rosmill/job/run_job.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include "job_setup.hpp"
#include "operation_engagement.hpp"
#include "rosmill/number_text.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/seconds_since.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/plan_params.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/segment/surface_patches.hpp"
#include "rosmill/stock/body_collision.hpp"
#include "rosmill/stock/fixture_collision.hpp"
#include "rosmill/toolpath/move_place.hpp"
#include "rosmill/toolpath/toolpath_stats.hpp"
#include "rosmill/gcode/cycle_time.hpp"
#include "rosmill/verify/gcode_reader.hpp"
#include "rosmill/verify/indexed.hpp"
#include "rosmill/verify/verify.hpp"

namespace rosmill::core::job {
namespace {

// Material above the design and the allowance thinner than this (mm) is nothing left to cut: the stock model's
// own rounding is well below it, a cut of it well above the finest tolerance anyone mills to.
constexpr double kNothingLeft = 0.01;

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

// A cell of the setup's view where the design stands above the floor and the stock has material.
bool on_part(const JobSetup& s, const stock::HeightField& view, size_t c) {
  return s.design[c] > s.floor + 1e-6 && view.top[c] != stock::kNoMaterial;
}

// The least and the most material the stock leaves on the part, seen from the setup: the stock's top minus the
// design's, over the cells the design covers (above the floor it stands on). Negative: a gouge.
std::pair<double, double> material_left(const JobSetup& s, const stock::HeightField& view) {
  double lo = INFINITY, hi = -INFINITY;
  for (size_t c = 0; c < s.design.size(); ++c) {
    if (!on_part(s, view, c)) continue;
    const double left = double(view.top[c]) - s.design[c];
    lo = std::min(lo, left);
    hi = std::max(hi, left);
  }
  return {lo, hi};
}

// Where the tool is after a job's last move.
Vec3 last_position(const Job& toolpaths) {
  for (auto t = toolpaths.rbegin(); t != toolpaths.rend(); ++t)
    for (auto p = t->passes.rbegin(); p != t->passes.rend(); ++p)
      if (!p->moves.empty()) return p->moves.back().to;
  return toolpaths.empty() ? Vec3::Zero() : toolpaths.back().start;
}

// The deepest cut below the design by the operation's program and the toolpath move that made it (0: none), from
// the verifier, which sweeps the program over a fresh height field of the part in the setup's frame, apart from
// the stock the operations carry: a second opinion on the gouge that the stock's material left gives.
std::pair<double, uint32_t> verified_gouge(const JobSetup& s, const stock::MachineProgram& program, double cell) {
  if (program.moves.empty()) return {0.0, 0};
  verify::VerifyOptions o;
  o.resolution = cell;
  const verify::DeviationReport d = verify::verify_program(s.part, program, verify::StockSpec{}, o).report;
  return {d.gouged ? d.max_gouge_mm : 0.0, d.gouged ? d.gouge_source : 0};
}

// What planning is told of the stock: its top from the setup (and the fixture's, which links clear), the top of the
// material the operation may remove (above the design and the allowance by more than kNothingLeft), and the cells
// it keeps to: the faces its setup finishes (finishing), and, for a rest operation, where more than the allowance
// and the threshold is left. Returns the cells with material to remove where the operation works.
size_t material_for(const JobSetup& s, const stock::HeightField& view, const OperationSpec& op, bool roughing,
                    MaterialTop& m, size_t& rest_cells) {
  const stock::GridSpec& g = view.grid;
  m.x0 = g.x0, m.y0 = g.y0, m.cell = g.cell, m.nx = g.nx, m.ny = g.ny;
  m.top = view.top;
  m.fixture = s.fixture_top;
  m.cut.assign(m.top.size(), -INFINITY);
  m.keep.clear();
  m.keep_low.clear();
  m.keep_high.clear();
  const bool by_faces = !roughing && !s.faces.empty();
  if (by_faces || op.rest) m.keep.assign(m.top.size(), 0);
  if (by_faces) m.keep_low = s.face_low, m.keep_high = s.face_high;
  size_t work = 0;
  rest_cells = 0;
  for (size_t c = 0; c < m.top.size(); ++c) {
    // The design's highest within the cell (its centre height would make every steep flank material to cut).
    const bool above = m.top[c] - s.design_high[c] > op.allowance + kNothingLeft;
    if (above) m.cut[c] = m.top[c];
    const bool rest = op.rest && on_part(s, view, c) && m.top[c] - s.design_high[c] > op.allowance + op.rest_threshold;
    rest_cells += rest;
    if (!m.keep.empty()) m.keep[c] = (!by_faces || s.faces[c]) && (!op.rest || rest);
    work += above && (m.keep.empty() || m.keep[c]);
  }
  return work;
}

// The material grid grown by what the tool reaches beyond the stock, with the fixture on it. The stock's own grid
// ends at its faces, and the jaws and clamps beside them would not be seen: a cutter clearing the stock's edges
// (adaptive clearing works up to 2R + 1 past the stock), and its shank and holder above, must keep clear of them.
void see_fixture_beside_stock(const fixture::Fixture& fixture, const Tool& tool, double link_clearance,
                              MaterialTop& m) {
  const double R = tool.cutter.radius();
  const double body = std::max({R, 0.5 * tool.cutter.shank_diameter, 0.5 * tool.holder_mm()});
  m.pad(static_cast<int>(std::ceil((2 * R + 1 + body + link_clearance + kFixtureCheckClearance) / m.cell)));
  stock::GridSpec g;
  g.x0 = m.x0, g.y0 = m.y0, g.cell = m.cell, g.nx = m.nx, g.ny = m.ny;
  m.fixture = fixture_tops(fixture, g);
}

// Plans one operation in its setup on the stock as it is; `nothing` tells when it had nothing to cut.
Job plan_operation(const JobSetup& s, const stock::InProcessStock& stock, const JobSpec& job, const OperationSpec& op,
                   const JobOptions& options, const std::string& where, const PlanProgress& progress,
                   OperationReport& r) {
  const PlanKind kind = plan_kind(op.strategy, options.presets, where + ".strategy");
  PlanningRequest request;
  // The part is already turned: the planner gets it in the setup's frame (a strategy that slices the mesh sees
  // the part alone; every other the part with the fixture kept clear of).
  if (kind.needs_mesh) request.input.mesh = &s.part;
  // A strategy that follows the material keeps clear of the fixture through the material grid, by the height band
  // of each part of the tool (see_fixture_beside_stock): its walls are the part's alone. The fixture as a surface
  // would add walls that enclose the part's own, and a level's region would take the part for a hole.
  else if (kind.follows_material && options.plan_on_stock) request.input.surface = s.part_surface.get();
  else request.input.surface = &s.surface();
  request.strategy = op.strategy;
  request.presets = options.presets;
  try {
    request.params.tool = resolve_tool(op.tool, options.tools);
  } catch (const Error& e) {
    throw Error(where + ".tool", e.what());
  }
  request.params.stepover = op.stepover;
  request.params.engagement_deg = op.engagement;
  if (options.checks.machine) request.params.max_feed = options.checks.machine->max_feed;
  request.params.stepdown = op.stepdown;
  request.params.allowance = op.allowance;
  if (!std::isnan(op.tolerance)) request.params.tolerance = op.tolerance;
  if (!std::isnan(op.angle)) request.params.angle_deg = op.angle;
  if (job.stock.kind == StockSpec::Kind::Box) request.params.stock_margin = job.stock.margin;
  if (s.stock_mesh) request.params.stock_mesh = &*s.stock_mesh;
  request.params.link_clearance = options.link_clearance;
  request.progress = progress;
  r.tool = request.params.tool.name;
  r.tool_used = request.params.tool;
  r.roughing = kind.roughing;
  request.reports = &r.plan_reports;
  if (!options.plan_on_stock) return plan(request);
  MaterialTop material;
  const size_t work = material_for(s, stock.view(s.report.frame), op, kind.roughing, material, r.rest_cells);
  if (!s.report.fixture.empty())
    see_fixture_beside_stock(s.report.fixture, request.params.tool, request.params.link_clearance, material);
  request.params.material = &material;
  // Roughing (and rest machining) with nothing above the design and the allowance where it works: no move at all,
  // not passes in air. A finishing operation runs: material left on a wall, beside the tool axis, does not show
  // in the stock's top seen along it.
  if (work == 0 && (kind.roughing || op.rest)) {
    r.nothing_to_cut = true;
    return {};
  }
  return plan(request);
}

// The operation's engagement against the stock before it (EngagementStock::prepare has read it); a roughing
// operation's feeds set from it (toolpaths and program both), and its removal rate then timed by those feeds.
void measure_operation(stock::MachineProgram& program, Job& toolpaths, EngagementStock& engagement,
                       const JobOptions& options, OperationReport& r) {
  r.engagement = engagement.measure(program);
  r.engagement_measured = true;
  if (r.roughing && options.feeds_from_engagement) {
    const double max_feed = options.checks.machine ? options.checks.machine->max_feed : 0.0;
    r.feeds_from_engagement = set_feeds_from_engagement(toolpaths, r.engagement.move_deg, max_feed);
    program = stock::program_from_job(toolpaths);
    verify::retime_engagement(r.engagement, program);
  }
  r.engagement.move_deg = {};
}

// Every operation runs the same stages, in order (as noether chains its planner and its modifiers):
//   plan           the strategy on the stock as it stands (plan_operation), then the toolpaths held as the
//                  machine holds the part (hold_on_machine)
//   crash checks   the tool, its shank and its holder against the fixture; the shank and the holder against the
//                  material the stock holds
//   cut            side by side: the engagement against the stock before the cut and a roughing's feeds from it;
//                  the moves removed from the stock; the verifier's sweep over a fresh height field of the part
//   verification   a rapid into the stock, the material left, a cut below the design (verify_cut)
//   timing         the program as the post writes it, timed as the controller's planner runs it, and the turn of
//                  the part before it on a machine that turns it (time_operation)
// A stage that finds a crash or a cut below the design refuses the job: no program is written.

// On a machine that turns the part, each toolpath is in the machine's frame at its setup's A and C: the post
// indexes there.
void hold_on_machine(Job& toolpaths, const SetupReport& setup) {
  if (!setup.index) return;
  for (Toolpath& tp : toolpaths) tp.indexed = true, tp.a = setup.index->a, tp.c = setup.index->c;
}

// The crash checks: a tool, shank or holder in the fixture, a shank or holder in the stock's material.
void crash_checks(const stock::MachineProgram& program, const SetupReport& sr, const stock::InProcessStock& stock,
                  const std::string& where) {
  if (const auto hit = stock::first_fixture_collision(program, sr.fixture))
    throw Error(where, hit->message() + " of its toolpaths: move the fixture, grip lower, or leave that area to "
                                        "another setup");
  if (const auto hit = stock::first_body_collision(program, stock, sr.frame))
    throw Error(where, hit->message() + " of its toolpaths: a longer tool (stick_out), or leave that depth to "
                                        "another setup");
}

// The cut: the feeds from the engagement, the removal and the verification, on both cores. The three read the
// moves' geometry, which the feeds do not change; the engagement reads the stock before the removal changes it.
stock::RemovalReport cut(stock::MachineProgram& program, Job& toolpaths, const JobSetup& setup,
                         stock::InProcessStock& stock, EngagementStock& engagement, const JobOptions& options,
                         double resolution, OperationReport& r) {
  const SetupFrame& frame = setup.report.frame;
  const bool measure = options.measure_engagement && !program.moves.empty();
  if (measure) engagement.prepare(program, stock, frame, r.setup_index);
  const stock::MachineProgram geometry = program;
  stock::RemovalReport removal;
  run_both(
      [&] {
        const auto t0 = std::chrono::steady_clock::now();
        if (measure) measure_operation(program, toolpaths, engagement, options, r);
        r.engagement_seconds = seconds_since(t0);
      },
      [&] {
        run_both([&] { removal = stock.remove(geometry, frame); },
                 [&] {
                   const auto t0 = std::chrono::steady_clock::now();
                   std::tie(r.gouge_mm, r.gouge_move) = verified_gouge(setup, geometry, resolution);
                   r.verify_seconds = seconds_since(t0);
                 });
      });
  return removal;
}

// What the cut did: a rapid through material is a crash, and a cut into the design, as the independent simulation
// finds it, is a defect of the plan, never a figure to report beside a program; either refuses the job (no
// program is written). Else the operation's figures: removal, air, the material left seen from the setup.
void verify_cut(const stock::RemovalReport& removal, const stock::MachineProgram& program, const JobSetup& setup,
                const stock::InProcessStock& stock, const Job& toolpaths, const std::string& where,
                const std::string& named, OperationReport& r) {
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
  std::tie(r.min_left_mm, r.max_left_mm) = material_left(setup, stock.view(setup.report.frame));
  if (r.gouge_mm > 0)
    throw Error(named, "the verifier finds the cutter " + decimal_text(r.gouge_mm, 3) +
                           " mm below the design at toolpath " + move_place(toolpaths, r.gouge_move) +
                           " (setup frame, mm): no program is written");
  for (const Toolpath& tp : toolpaths) {
    const ToolpathStats st = toolpath_stats(tp);
    r.cutting_mm += st.cutting_length;
    r.rapid_mm += st.rapid_length;
  }
}

// Where a machine that turns the part last turned it, and the machine z of the tool when the next turn begins.
struct IndexingClock {
  std::optional<machine::Index> at;  // none: not yet
  double tool_z = 0;
};

// The operation's program as the post writes it, timed as the controller's planner runs it; on a machine that
// turns the part, the turn before it (the post indexes before the program's first toolpath and wherever A or C
// change), counted in the setup's time and the job's.
void time_operation(const Job& toolpaths, const machine::Machine& machine, const JobSpec& job,
                    const JobOptions& options, IndexingClock& clock, JobReport& report, OperationReport& r) {
  if (toolpaths.empty()) return;
  const machine::Trunnion* trunnion = machine.trunnion();
  // The operation's own moves: on a machine that turns the part, without the retract, turn and way down the post
  // writes before an indexed toolpath (the indexing clock below counts them once per turn, as the program runs them).
  Job moves = toolpaths;
  for (Toolpath& tp : moves) tp.indexed = false;
  r.time_s = gcode::estimate_cycle_time(moves, gcode::post_options_for(options.dialect), options.trajectory).seconds;
  SetupReport& setup = report.setups.back();
  if (!setup.index) return;
  const machine::Index& to = *setup.index;
  // The retract and the way down are rapids along Z: at the machine's Z speed when the machine file gives it.
  const double z_speed = options.trajectory.max_velocity.z();
  const double rapid_feed = z_speed > 0 ? 60 * z_speed : job.rapid_feed;
  if (!clock.at || clock.at->a != to.a || clock.at->c != to.c) {
    const double s = indexing_seconds(*trunnion, clock.at.value_or(machine::Index{}), to, clock.tool_z,
                                      std::max(toolpaths.front().clearance_z, toolpaths.front().start.z()), rapid_feed,
                                      options.trajectory.max_acceleration);
    setup.indexing_s += s;
    setup.time_s += s;
    report.time_s += s;
    clock.at = to;
  }
  clock.tool_z = last_position(toolpaths).z();
}

// The job's totals of the feed path, for the share that cut only air.
struct JobTotals {
  double feed_mm = 0, air_mm = 0;
};

// The operation's figures added to its setup's and the job's.
void add_operation(const OperationReport& r, const stock::RemovalReport& removal, JobTotals& totals,
                   JobReport& report) {
  totals.feed_mm += removal.feed_mm;
  totals.air_mm += removal.air_feed_mm;
  report.removed_mm3 += r.removed_mm3;
  report.time_s += r.time_s;
  report.gouge_mm = std::max(report.gouge_mm, r.gouge_mm);
  report.setups.back().operations.push_back(report.operations.size());
  report.setups.back().time_s += r.time_s;
  report.operations.push_back(r);
}

// The report of an operation before it runs: what the job names.
OperationReport operation_report(const OperationSpec& op) {
  OperationReport r;
  r.name = op.name;
  r.strategy = op.strategy;
  r.setup = op.setup;
  r.setup_index = op.setup_index;
  r.rest = op.rest;
  return r;
}

// The job's setups: as the job names them, or chosen from the segmentation; and who finishes which faces.
struct Setups {
  std::vector<SetupSpec> specs;
  std::vector<OperationSpec> operations;
  std::optional<setups::SetupChoice> faces;
  std::vector<int> chosen;  // per setup, its index in faces->setups (-1: it finishes no face)
};

// The room the job's machine has for a setup clamped on its table (none for a machine that turns the part, whose
// setups share one clamping, or without a machine).
std::optional<setups::MachineRoom> machine_room(const std::vector<OperationSpec>& operations,
                                                const machine::Machine& machine, const JobOptions& options) {
  const std::optional<gcode::MachineLimits>& m = options.checks.machine;
  if (!m || machine.turns_part()) return std::nullopt;
  setups::MachineRoom room;
  room.name = m->name;
  room.travel = m->envelope;
  room.table_z = m->table_z;
  room.fixture_position = m->fixture_position;
  room.clearance = PlanParams{}.safe_clearance;
  for (const OperationSpec& op : operations)  // adaptive clearing works up to 2R + 1 past the stock
    room.beyond = std::max(room.beyond, resolve_tool(op.tool, options.tools).cutter.diameter + 1.0);
  return room;
}

// A job whose surface some setup is needed for, and whose every such setup does not fit the machine, is refused
// before anything is planned (unless it accepts faces left unfinished).
void refuse_unfit(const JobSpec& job, const setups::SetupChoice& choice) {
  double lost = 0;
  for (size_t k = 0; k < choice.samples.size(); ++k)
    if (choice.unmachined[k] == setups::Unmachined::Machine) lost += choice.samples.weights[k];
  if (job.accept_unfinished || lost <= job.auto_options.min_gain * choice.total_area) return;
  std::string why;
  for (size_t c = 0; c < choice.candidates.size(); ++c)
    if (choice.candidate_unfit[c]) why += "; " + choice.candidates[c].name + ": " + choice.candidate_refused[c];
  throw Error(job.source + " setups",
              decimal_text(lost, 1) + " mm2 of the part are reached only by setups that do not fit the machine" + why +
                  " (a smaller fixture or stock, another machine, or accept_unfinished: true to machine the rest)");
}

Setups resolve_setups(const JobSpec& job, const Mesh& part, const stock::InProcessStock& stock,
                      const machine::Machine& machine, const JobOptions& options) {
  Setups out;
  out.specs = job.setups;
  out.operations = job.operations;
  if (!job.auto_setups && !job.finish_by_setup) return out;
  // The finishing tool's reach decides who finishes what: the last operation's tool (auto: the one named).
  setups::ChoiceOptions o;
  const std::string tool = !job.auto_options.tool.empty() ? job.auto_options.tool : job.operations.back().tool;
  try {
    o.tool = resolve_tool(tool, options.tools);
  } catch (const Error& e) {
    throw Error(job.source + " auto.tool", e.what());
  }
  o.min_gain_share = job.auto_options.min_gain;
  o.held_face = job.auto_options.held_face;
  o.stock = stock.bounds_in(SetupFrame{});
  if (job.auto_setups) o.machine = machine_room(job.operations, machine, options);
  // On a machine that turns the part a direction is a setup only where its joints can bring it under the spindle.
  if (job.auto_setups && machine.turns_part())
    o.direction_refused = [&machine](const Vec3& d) {
      std::string why;
      return machine.setup_joints(d, machine.home(), &why) ? std::string()
                                                           : "this machine cannot index the part for it: " + why;
    };
  if (job.auto_setups && job.setup_defaults.fixture.kind != fixture::FixtureSpec::Kind::None)
    o.fixture = job.setup_defaults.fixture;
  if (!job.auto_setups) {
    o.search = false;
    for (const SetupSpec& s : job.setups) o.directions.push_back(s.direction);
  }
  const segment::SurfacePatches patches = segment::segment_surface(part);
  out.faces = setups::choose_setups(part, patches, o);
  if (!job.auto_setups) {
    // The job's setups are the candidates in order: each finishes what the choice gave its candidate.
    out.chosen.assign(job.setups.size(), -1);
    for (size_t i = 0; i < out.faces->setups.size(); ++i) out.chosen[out.faces->setups[i].candidate] = int(i);
    return out;
  }
  if (out.faces->setups.empty()) throw Error(job.source + " setups", "no candidate setup reaches the part");
  refuse_unfit(job, *out.faces);
  if (out.faces->setups.size() > size_t(gcode::kWorkOffsets))
    throw Error(job.source + " setups", std::to_string(out.faces->setups.size()) +
                                           " setups chosen, more than the six work offsets (G54..G59)");
  out.specs.clear();
  out.operations.clear();
  for (const setups::ChosenSetup& c : out.faces->setups) {
    SetupSpec s = default_setup(job, c.direction);
    s.name = c.name == "custom" ? "custom " + std::to_string(out.specs.size() + 1) : c.name;
    for (OperationSpec op : job.operations) {
      op.setup = s.name;
      op.setup_index = out.specs.size();
      out.operations.push_back(op);
    }
    out.chosen.push_back(int(out.specs.size()));
    out.specs.push_back(s);
  }
  return out;
}

// Every operation's tool resolved before anything is planned: one number is one cutter in all of the job's
// programs (a tool of the table and an inline tool with its number must not share one).
void check_tool_numbers(const std::vector<OperationSpec>& operations, const JobOptions& options,
                        const std::string& source) {
  std::vector<std::pair<Tool, size_t>> seen;
  for (size_t k = 0; k < operations.size(); ++k) {
    const std::string where = source + ":" + std::to_string(operations[k].line) + " operations[" +
                              std::to_string(k) + "].tool";
    Tool t;
    try {
      t = resolve_tool(operations[k].tool, options.tools, where);
    } catch (const Error& e) {
      throw Error(where, e.what());
    }
    for (const auto& [other, at] : seen)
      if (other.id == t.id && !same_cutter(other.cutter, t.cutter))
        throw Error(where, "tool T" + std::to_string(t.id) + " is another cutter in operations[" + std::to_string(at) +
                               "] (" + operations[at].tool + "): one number, one tool");
    seen.emplace_back(t, k);
  }
}

std::string setup_note(const SetupReport& s, size_t index) {
  return "for setup " + std::to_string(index + 1) + " (" + s.name + "): the datum, " + datum_name(s.datum) +
         " of the stock, with the part " + s.face_down + " down in its fixture";
}

// The job's programs: one per setup (the part stays clamped; the tools change with M6 T between its operations),
// or one per operation on request, each setting its setup's work offset. Every program is prepared and checked
// before any is written, so a job that fails a check leaves no program behind.
void write_programs(const JobSpec& job, const std::vector<Job>& planned, const machine::Machine& machine,
                    const JobOptions& options, JobReport& report) {
  std::vector<std::pair<std::string, gcode::Program>> programs;
  // Every rapid was swept through the in-process stock, which knows the stock's top under it: the links low over
  // the material need not clear the whole stock's top.
  gcode::ProgramChecks checks = options.checks;
  checks.limits.rapids_checked_by_stock = true;
  for (const auto& [first, end] : program_groups(report, options.per_operation)) {
    Job toolpaths;
    for (size_t k = first; k < end; ++k) toolpaths.insert(toolpaths.end(), planned[k].begin(), planned[k].end());
    if (toolpaths.empty()) continue;  // its operations had nothing to cut
    const size_t index = report.operations[first].setup_index;
    SetupReport& setup = report.setups[index];
    const std::string name = options.per_operation ? report.operations[first].name
                             : report.indexed        ? "setups indexed 3+2"
                                                     : "setup " + setup.name;
    const std::string path = program_path(options.out_dir, programs.size(), name);
    gcode::PostOptions post = gcode::post_options_for(options.dialect);
    post.title = "rosmill job " + job.source + ": " + name + ", " + setup.face_down + " down, " +
                 setup.fixture.description;
    post.work_offset = setup.work_offset;
    post.work_offset_note = setup_note(setup, index);
    if (report.indexed) {
      post.index_safe_z = machine.trunnion()->safe_z;
      post.select_identity = machine.simultaneous();  // its programs may have left it in tool-centre-point kinematics
      post.work_offset_note = "at machine zero: identity kinematics, the program's X Y Z are the machine's axes "
                              "(the simulator starts in them, and LinuxCNC's rs274 reads the program as it runs)";
      post.title = "rosmill job " + job.source + ": " + std::to_string(report.setups.size()) +
                   " setups indexed on the trunnion (3+2), one clamping: " + setup.fixture.description;
    }
    try {
      programs.emplace_back(path, gcode::prepare_program(toolpaths, post, checks).program);
    } catch (const Error& e) {
      throw Error("setup " + std::to_string(index + 1) + " (" + setup.name + ") program", e.what());
    }
    for (size_t k = first; k < end; ++k) {
      report.operations[k].program = path;
      report.setups[report.operations[k].setup_index].program = path;  // 3+2: every setup's
    }
  }
  std::filesystem::create_directories(options.out_dir);
  for (const auto& [path, program] : programs) gcode::write_program(path, program);
}

// The written 3+2 program read back from its file (the tools as planned) and simulated through its rotary moves
// from the raw stock: the final stock against the design in the workpiece frame, whatever A and C did.
void check_indexed_program(const JobSpec& job, const machine::Trunnion& trunnion, const Mesh& part,
                           const Mesh* stock_mesh, const Box3& raw_box, const std::vector<Job>& planned, JobReport& report) {
  const std::string& path = report.setups.front().program;
  if (path.empty()) return;
  verify::ToolSetup tools;
  tools.rotary = true;
  for (const Job& j : planned)
    for (const Toolpath& tp : j) tools.tools.emplace(tp.tool.id, tp.tool);
  verify::StockSpec stock;
  if (stock_mesh) {
    stock.kind = verify::StockSpec::Kind::Mesh;
    stock.mesh = stock_mesh;
  } else {
    stock.kind = verify::StockSpec::Kind::Box;
    stock.box = raw_box;
  }
  verify::VerifyOptions o;
  o.resolution = job.resolution;
  const verify::IndexedVerifyResult v =
      verify::verify_indexed(part, verify::read_gcode(path, tools), trunnion, *report.workpiece_on_table, stock, o);
  JobReport::ProgramCheck& c = report.program_check;
  c.done = true;
  c.runs = v.runs.size();
  c.gouge_mm = v.max_gouge_mm;
  c.gouge_line = v.gouge_source;
  c.min_left_mm = v.min_left_mm;
  c.max_left_mm = v.max_left_mm;
  c.left_mm3 = v.left_mm3;
  c.seconds = v.seconds;
}

// Who machines which sample, for a job that did not choose its setups by faces (the older form, every operation
// over the whole part): each of its setups' directions is a candidate, and reaches what it reaches.
setups::SetupChoice reach_of_setups(const JobSpec& job, const Mesh& part, const JobReport& report,
                                    const JobOptions& options, const Box3& raw_box) {
  setups::ChoiceOptions o;
  o.tool = resolve_tool(job.operations.back().tool, options.tools);
  o.search = false;
  o.stock = raw_box;
  for (const SetupReport& s : report.setups) o.directions.push_back(s.direction);
  return setups::choose_setups(part, segment::segment_surface(part), o);
}

// The material left on the whole part after the job (surface_account.hpp).
SurfaceAccount account_of_job(const JobSpec& job, const std::vector<OperationSpec>& operations, const Setups& setups,
                              const Mesh& part, const stock::InProcessStock& stock, const JobReport& report,
                              const JobOptions& options, const Box3& raw_box) {
  std::optional<setups::SetupChoice> own;
  if (!setups.faces) own = reach_of_setups(job, part, report, options, raw_box);
  const setups::SetupChoice& choice = setups.faces ? *setups.faces : *own;
  AccountInput in;
  in.part = &part;
  in.stock = &stock;
  in.choice = &choice;
  in.whole_part = job.auto_setups;
  in.job_setup.assign(choice.setups.size(), -1);
  for (size_t j = 0; j < report.setups.size(); ++j) {
    const int c = setups.faces ? setups.chosen[j] : int(j);
    if (c >= 0 && size_t(c) < choice.setups.size()) in.job_setup[size_t(c)] = int(j);
    in.setups.push_back({report.setups[j].frame, report.setups[j].fixture});
  }
  for (size_t k = 0; k < report.operations.size(); ++k) {
    const OperationReport& r = report.operations[k];
    const OperationSpec& spec = operations[k];
    AccountOperation op;
    op.setup = r.setup_index;
    op.finishing = !r.roughing;
    op.tool = r.tool_used;
    op.allowance = spec.allowance;
    op.tolerance = std::isnan(spec.tolerance) ? kDefaultTolerance : spec.tolerance;
    op.scallop = nominal_scallop(op.tool.cutter, spec.strategy, std::isnan(spec.stepover) ? op.tool.stepover
                                                                                          : spec.stepover,
                                 std::isnan(spec.stepdown) ? op.tool.stepdown : spec.stepdown);
    in.operations.push_back(op);
  }
  in.march_step = std::max(0.05, 0.5 * job.resolution);
  return account_surface(in);
}

// The kind of machine the job runs on: its machine file's, or a 3-axis mill without limits when it has none.
std::shared_ptr<const machine::Machine> machine_of(const JobOptions& options) {
  if (options.checks.machine) return options.checks.machine->machine();
  const Box3 anywhere{Vec3::Constant(-INFINITY), Vec3::Constant(INFINITY)};
  return machine::three_axis_mill(anywhere, Vec3::Zero(), Vec3::Zero());
}

// A registration places the part as it sits: the setup whose datum is the part's own origin (the others' fixtures
// place them on the table). Two such setups cannot both be where it found the part.
void refuse_two_registered_setups(const JobSpec& job, const Setups& setups, const JobOptions& options) {
  const size_t at_workpiece = std::count_if(setups.specs.begin(), setups.specs.end(),
                                            [](const SetupSpec& s) { return s.datum == Datum::Workpiece; });
  if (options.work_offset && at_workpiece > 1)
    throw Error(job.source, "a registered work offset places the part of one setup; " + std::to_string(at_workpiece) +
                                " of this job's setups have the workpiece datum");
}

// What setup selection found, in the report: the surface no setup reaches, and per facet the setup that finishes it
// (the choice's own indices turned into the job's).
void report_chosen_setups(const JobSpec& job, const Setups& setups, const Mesh& part, JobReport& report) {
  report.setups_chosen = job.auto_setups;
  report.part_area = setups.faces->total_area;
  report.unreachable_area = setups.faces->unreachable_area;
  report.unreachable = setups.faces->unreachable;
  report.facet_setup = setups::facet_setups(*setups.faces, part.face_count());
  for (int& s : report.facet_setup)
    if (s >= 0) s = int(std::find(setups.chosen.begin(), setups.chosen.end(), s) - setups.chosen.begin());
}

// The setup `index` begins on the stock as the operations before left it; on a machine that turns the part, the
// turn from the setup before is first swept for a collision with the retracted tool.
JobSetup next_setup(const Setups& setups, size_t index, const stock::InProcessStock& stock, const SetupContext& context,
                    JobReport& report) {
  const JobSpec& job = context.job;
  const TableSetting* table = context.table;
  SetupContext c = context;
  c.chosen = setups.faces ? setups.chosen[index] : -1;
  const machine::Index before = table ? machine::index_of(table->last) : machine::Index{};
  JobSetup setup = begin_setup(setups.specs[index], index, stock, c);
  if (table)
    check_indexing(stock, *table, before, *setup.report.index, context.options.checks.machine->clearance_over_stock,
                   job.source + " setups[" + std::to_string(index) + "] (" + setup.report.name + ")");
  setup.report.source = job.auto_setups ? setups.faces->setups[size_t(setups.chosen[index])].source : "given";
  report.setups.push_back(setup.report);
  return setup;
}

}  // namespace

Mesh read_part(const JobSpec& job) { return read_mesh(job.part, job.units); }

std::vector<std::pair<size_t, size_t>> program_groups(const JobReport& report, bool per_operation) {
  std::vector<std::pair<size_t, size_t>> groups;
  const auto& ops = report.operations;
  // A trunnion's setups are one program: the part is indexed between them, not re-clamped.
  if (report.indexed && !per_operation) {
    if (!ops.empty()) groups.emplace_back(0, ops.size());
    return groups;
  }
  for (size_t first = 0; first < ops.size();) {
    size_t end = first + 1;
    while (!per_operation && end < ops.size() && ops[end].setup_index == ops[first].setup_index) ++end;
    groups.emplace_back(first, end);
    first = end;
  }
  return groups;
}

// The job's stages follow a tool along +Z of each setup: the stock's removal and checks, the feeds, the 3+2 post.
// An operation whose strategy tilts the tool at every move is refused before anything is planned, naming it,
// rather than cut and checked as if the tool stood up.
void refuse_multi_axis(const JobSpec& job, const std::vector<OperationSpec>& ops, const JobOptions& options) {
  for (size_t k = 0; k < ops.size(); ++k) {
    const OperationSpec& op = ops[k];
    const std::string where = job.source + ":" + std::to_string(op.line) + " operations[" + std::to_string(k) + "]";
    if (!plan_kind(op.strategy, options.presets, where + ".strategy").multi_axis) continue;
    throw Error(
        where + " (" + op.name + ")",
        "strategy '" + op.strategy +
            "' gives a tool axis at every move, and a job does not yet cut, check and "
            "post such an operation: finish the part with `rosmill plan PART --strategy " +
            op.strategy +
            " --machine` a tool-centre-point machine file (config/machine_xyzac_tcp.yaml), then `rosmill verify`");
  }
}

JobReport run_job(const JobSpec& job, const JobOptions& options) {
  const Mesh part = options.part ? *options.part : read_part(job);
  std::optional<Mesh> stock_mesh;
  if (job.stock.kind == StockSpec::Kind::Mesh) stock_mesh = read_mesh(job.stock.file, job.units);
  stock::InProcessStock stock = raw_stock(job, part, stock_mesh ? &*stock_mesh : nullptr);
  const Box3 raw_box = stock.bounds_in(SetupFrame{});  // for the 3+2 program's check
  JobReport report;
  report.stock_mm3 = stock.volume();
  report.stock_box = raw_box;
  check_tool_numbers(job.operations, options, job.source);
  const std::shared_ptr<const machine::Machine> machine = machine_of(options);
  const Setups setups = resolve_setups(job, part, stock, *machine, options);
  refuse_multi_axis(job, setups.operations, options);
  if (options.operations_known) options.operations_known(setups.operations);
  refuse_two_registered_setups(job, setups, options);
  if (setups.faces) report_chosen_setups(job, setups, part, report);
  SetupContext context{job, options, part, stock_mesh ? &*stock_mesh : nullptr,
                       setups.faces ? &*setups.faces : nullptr, 0};
  // A machine that turns the part holds it in one clamping through the setups (3+2): placed on its table once.
  std::optional<TableSetting> table;
  if (machine->turns_part()) {
    table = place_on_table(*machine, setups.specs.front().fixture, stock, options, job.source + " setups[0]");
    context.table = &*table;
    report.indexed = true;
    report.workpiece_on_table = table->workpiece_on_table;
  }
  JobTotals totals;
  IndexingClock clock;
  if (const machine::Trunnion* t = machine->trunnion()) clock.tool_z = t->safe_z;
  std::vector<Job> planned;  // each operation's toolpaths, for the programs
  std::optional<JobSetup> setup;
  EngagementStock engagement;
  const auto go_on = [&](size_t k, double fraction) { return !options.progress || options.progress(k, fraction); };
  for (size_t k = 0; k < setups.operations.size(); ++k) {
    if (!go_on(k, 0.0)) {
      report.cancelled = true;
      break;
    }
    const OperationSpec& op = setups.operations[k];
    if (!setup || op.setup_index != report.setups.size() - 1)
      setup = next_setup(setups, op.setup_index, stock, context, report);
    const std::string where = job.source + ":" + std::to_string(op.line) + " operations[" + std::to_string(k) + "]";
    OperationReport r = operation_report(op);
    // Stage plan: the strategy on the stock as it stands. It takes the first 90 % of the operation's progress,
    // the removal from the stock the rest.
    bool stopped = false;
    const PlanProgress progress = [&](double f) { return !(stopped = !go_on(k, 0.9 * f)); };
    auto t0 = std::chrono::steady_clock::now();
    Job toolpaths;
    try {
      toolpaths = plan_operation(*setup, stock, job, op, options, where, progress, r);
    } catch (const Error&) {
      if (!stopped) throw;
      report.cancelled = true;
      break;
    }
    r.plan_seconds = seconds_since(t0);
    const SetupReport& sr = report.setups.back();
    hold_on_machine(toolpaths, sr);
    stock::MachineProgram program = stock::program_from_job(toolpaths);
    const std::string named = where + " (" + op.name + ", setup " + sr.name + ")";
    // Stage crash checks.
    crash_checks(program, sr, stock, named);
    // Stage cut: feeds from the engagement, the removal and the verifier's sweep side by side.
    const stock::RemovalReport removal = cut(program, toolpaths, *setup, stock, engagement, options, job.resolution, r);
    // Stage verification: what the cut did to the stock and the design.
    verify_cut(removal, program, *setup, stock, toolpaths, where, named, r);
    // Stage timing: the program as the post writes it and the controller's planner runs it, and the indexing.
    time_operation(toolpaths, *machine, job, options, clock, report, r);
    planned.push_back(toolpaths);
    add_operation(r, removal, totals, report);
    if (options.operation_done)
      options.operation_done(
          {k, report.operations.back(), planned.back(), report.setups.back(), report.facet_setup, stock, part});
    if (!go_on(k, 1.0) && k + 1 < setups.operations.size()) {
      report.cancelled = true;
      break;
    }
  }
  if (!options.out_dir.empty()) {
    write_programs(job, planned, *machine, options, report);
    if (machine->turns_part() && !options.per_operation)
      check_indexed_program(job, *machine->trunnion(), part, stock_mesh ? &*stock_mesh : nullptr, raw_box, planned,
                            report);
  }
  report.left_mm3 = stock.volume();
  report.accept_unfinished = job.accept_unfinished;
  if (!report.cancelled && !report.operations.empty()) {
    report.surface = account_of_job(job, setups.operations, setups, part, stock, report, options, raw_box);
    report.min_left_mm = report.surface.min_left_mm;
    report.max_left_mm = report.surface.max_left_mm;
  }
  report.air_cut_share = totals.feed_mm > 0 ? totals.air_mm / totals.feed_mm : 0.0;
  report.stock_bytes = stock.bytes();
  return report;
}

}  // namespace rosmill::core::job
