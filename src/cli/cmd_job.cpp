// rosmill job JOB.yaml [-o DIR] [--json] [--tools FILE] [--presets FILE] [--dialect linuxcnc|grbl]
//   [--machine FILE | --no-limits] [--work-offset x,y,z[,deg] | --work-offset REGISTRATION.json]
// Runs the job's operations in order on the in-process stock: each planned, removed from the stock the ones
// before left, and with -o written through the checked program pipeline: one program per setup (DIR/NN_setup_S.ngc,
// tool changes between operations), or one per operation with --per-operation (DIR/NN_NAME.ngc). Prints per operation
// the material removed, the air-cutting share and the estimated time, and the same for the job. With -o also
// DIR/setup_sheet.html: per setup the fixture, the datum and work offset, the tools, the operations and a picture.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "command.hpp"
#include "progress_bar.hpp"
#include "config_file.hpp"
#include "work_offset_option.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/job/job_options.hpp"
#include "rosmill/job/job_progress.hpp"
#include "rosmill/job/run_job.hpp"
#include "rosmill/sheet/setup_sheet.hpp"

namespace rosmill::core::cli {
namespace {

struct JobArgs {
  std::string file, out, tools, presets, dialect = "linuxcnc", machine;
  bool json = false, no_limits = false, per_operation = false, table_feeds = false;
  WorkOffsetArgs work_offset;
};

// A length as printed to three decimals, without a "-0.000" from rounding.
double shown(double mm) { return std::abs(mm) < 5e-4 ? 0.0 : mm; }

// The whole surface after the job: every face the job was to finish and left above its limit, with where, how
// much and why.
void print_surface(const job::JobReport& r) {
  const job::SurfaceAccount& s = r.surface;
  if (!s.done) return;
  std::printf("faces: %zu to finish, %zu above their limit over %.1f mm2 (%zu surface samples, %.2f s)\n",
              s.asked_faces, s.unfinished_faces, s.unfinished_area, s.samples, s.seconds);
  for (const job::FaceLeft& f : s.faces) {
    if (f.verdict != job::FaceVerdict::Above) continue;
    const std::string setup = f.setup >= 0 ? "setup " + std::to_string(f.setup + 1) + " " + r.setups[f.setup].name
                                           : "no setup";
    // A face's normal is its area's mean: a curved face (an island's round wall) has none to show.
    char normal[64] = "curved";
    if (f.normal.norm() > 0.9)
      std::snprintf(normal, sizeof normal, "normal %.2f %.2f %.2f", shown(f.normal.x()), shown(f.normal.y()),
                    shown(f.normal.z()));
    std::printf("    face %u (%s, %s): %.1f of %.1f mm2 above %.3f mm, up to %.3f mm at %.2f %.2f %.2f: %s\n", f.face,
                setup.c_str(), normal, f.above_area, f.area, f.limit, f.max_left_mm, f.most_at.x(), f.most_at.y(),
                f.most_at.z(), job::reason_name(f.main_reason()));
  }
}

// What the operation's strategy itself says it slotted and could not clear (adaptive clearing), the first few
// patches of it in full.
void print_strategy_left(const job::OperationReport& op) {
  constexpr size_t kShown = 8;
  size_t patches = 0;
  double rest_area = 0;
  for (const PlanReport& p : op.plan_reports) {
    if (p.slot_length_mm > 0) std::printf("    %s\n", slot_text(p).c_str());
    for (const UnclearedPatch& l : p.uncleared)
      if (++patches <= kShown) std::printf("    %s (setup frame)\n", uncleared_text(l).c_str());
      else rest_area += l.area_mm2;
  }
  if (patches > kShown) std::printf("    ... and %zu more patches left, %.1f mm2\n", patches - kShown, rest_area);
}

// A job that leaves a face it was to finish above its limit fails (exit status 4) unless it accepts that.
void refuse_unfinished(const job::JobReport& r) {
  if (!r.unfinished()) return;
  std::fprintf(stderr,
               "rosmill: job: %zu faces it was to finish are left above their limit (%.1f mm2, up to %.3f mm): "
               "the next tool would meet that material (give the job accept_unfinished: true to accept it); exit "
               "status 4\n",
               r.surface.unfinished_faces, r.surface.unfinished_area, r.surface.max_left_mm);
  throw CLI::RuntimeError(4);
}

// The machine file's contents: --machine, else config/machine.yaml when there is one (see config_file.hpp).
std::optional<gcode::MachineLimits> machine_of(const JobArgs& a) {
  if (a.machine.empty() && !std::filesystem::exists(default_config("machine.yaml"))) return std::nullopt;
  return gcode::load_machine_limits(machine_file(a.machine));
}

void run(const JobArgs& a) {
  const job::JobSpec spec = job::read_job(a.file);
  const ToolTable tools = read_tool_table(a.tools.empty() ? default_config("tools.yaml") : a.tools);
  const PresetTable presets = read_presets(a.presets.empty() ? default_config("presets.yaml") : a.presets);
  job::JobRequest request;
  request.tools = &tools;
  request.presets = &presets;
  request.machine = machine_of(a);
  request.no_limits = a.no_limits;
  request.out_dir = a.out;
  request.per_operation = a.per_operation;
  request.dialect = a.dialect;
  request.table_feeds = a.table_feeds;
  if (!a.work_offset.given.empty() && a.out.empty())
    throw Error("--work-offset", "sets G54 in the written programs (G10 L2 P1): give -o DIR too");
  request.work_offset = [&a] { return work_offset_of(a.work_offset); };
  job::JobOptions o = job::job_options(request);
  // With -o, the setup sheet beside the programs: each operation's toolpaths for its setup's picture.
  sheet::SheetJob sheet;
  sheet.title = a.file;
  if (!a.out.empty()) o.operation_done = [&](const job::OperationView& v) { sheet.toolpaths.push_back(v.toolpaths); };
  ProgressBar bar(!a.json);
  job::report_progress(o, spec, [&bar](const job::JobProgress& p) {
    bar.update(p.name + " (" + std::to_string(p.operation + 1) + "/" + std::to_string(p.operations) + ", " + p.setup + ")",
               p.fraction);
    return true;
  });
  const job::JobReport r = job::run_job(spec, o);
  bar.clear();
  if (!a.out.empty()) {
    const Mesh part = job::read_part(spec);
    sheet.report = &r;
    sheet.part = &part;
    sheet::write_setup_sheet((std::filesystem::path(a.out) / "setup_sheet.html").string(), sheet);
  }
  if (a.json) {
    std::printf("%s\n", job::to_json(r).dump().c_str());
    refuse_unfinished(r);
    return;
  }
  std::printf("job %s: stock %.0f mm3 (model %.1f MB)\n", a.file.c_str(), r.stock_mm3, r.stock_bytes / 1e6);
  for (size_t k = 0; k < r.setups.size(); ++k) {
    const job::SetupReport& s = r.setups[k];
    const std::string offset = s.work_offset ? s.work_offset->code() : "G54 as set";
    std::printf("setup %zu %-8s %s down, %s; datum %s, %s", k + 1, s.name.c_str(), s.face_down.c_str(),
                s.fixture.description.c_str(), job::datum_name(s.datum), offset.c_str());
    if (s.work_offset)
      std::printf(" at machine %.3f %.3f %.3f", shown(s.work_offset->origin.x()), shown(s.work_offset->origin.y()),
                  shown(s.work_offset->origin.z()));
    if (s.finished_area > 0) std::printf("; finishes %.0f mm2", s.finished_area);
    if (s.index) std::printf("; indexed A %.4f C %.4f (%.1f s)", s.index->a, s.index->c, s.indexing_s);
    std::printf("\n");
  }
  if (r.part_area > 0) {
    std::printf("no setup machines %.0f of %.0f mm2 of the part\n", r.unreachable_area, r.part_area);
    for (const setups::Unreached& u : r.unreachable)
      std::printf("    %-11s %9.1f mm2 on patch %u around %.2f %.2f %.2f\n", u.reason.c_str(), u.area, u.patch,
                  u.centroid.x(), u.centroid.y(), u.centroid.z());
  }
  std::printf("%-3s %-16s %-12s %-10s %-5s %9s %12s %6s %9s %17s %s\n", "#", "operation", "strategy", "tool",
              "setup", "moves", "removed mm3", "air %", "time s", "left on part mm", "program");
  for (size_t k = 0; k < r.operations.size(); ++k) {
    const job::OperationReport& op = r.operations[k];
    std::printf("%-3zu %-16s %-12s %-10s %-5s %9zu %12.0f %6.1f %9.0f %8.3f..%-7.3f %s\n", k + 1, op.name.c_str(),
                op.strategy.c_str(), op.tool.c_str(), op.setup.c_str(), op.moves, op.removed_mm3,
                100 * op.air_cut_share, op.time_s, op.min_left_mm, op.max_left_mm, op.program.c_str());
    if (op.collision_line)
      std::printf("    rapid into material at toolpath move %u\n", op.collision_line);
    if (op.nothing_to_cut) std::printf("    nothing left to cut: not planned\n");
    if (op.engagement_measured)
      std::printf("    engagement max %.1f deg, p95 %.1f deg, %.0f mm3/min while feeding%s\n", op.engagement.max_deg,
                  op.engagement.p95_deg, op.engagement.mrr_mm3_per_min,
                  op.feeds_from_engagement ? "; feeds from engagement" : "");
    if (op.gouge_mm > 0)
      std::printf("    cuts %.3f mm below the design at toolpath move %u (the verifier)\n", op.gouge_mm, op.gouge_move);
    print_strategy_left(op);
  }
  std::printf("job: removed %.0f mm3, left %.0f mm3, air cutting %.1f %%, time %.0f s, material left on the %s "
              "%.3f to %.3f mm, deepest gouge (the verifier) %.3f mm\n",
              r.removed_mm3, r.left_mm3, 100 * r.air_cut_share, r.time_s,
              r.surface.asked_faces ? "faces it was to finish" : "part", shown(r.min_left_mm), shown(r.max_left_mm),
              r.gouge_mm);
  print_surface(r);
  if (r.program_check.done) {
    const job::JobReport::ProgramCheck& c = r.program_check;
    std::printf("3+2 program read back and simulated through its %zu indexings: deepest gouge %.3f mm%s, material "
                "left on the part %.3f to %.3f mm, %.0f mm3 over the design (%.2f s)\n",
                c.runs, c.gouge_mm, c.gouge_line ? (" at line " + std::to_string(c.gouge_line)).c_str() : "",
                c.min_left_mm, c.max_left_mm, c.left_mm3, c.seconds);
  }
  refuse_unfinished(r);
}

CommandRegistration reg([](CLI::App& app) {
  auto a = std::make_shared<JobArgs>();
  auto* cmd = app.add_subcommand("job", "run a job's operations on the in-process stock (see README: Jobs)");
  cmd->add_option("JOB", a->file, "the job file (YAML)")->required();
  cmd->add_option("-o", a->out,
                  "write the programs into this folder: one per setup (tool changes between operations), "
                  "NN_setup_S.ngc");
  cmd->add_flag("--per-operation", a->per_operation, "with -o: one program per operation, NN_NAME.ngc");
  cmd->add_flag("--json", a->json, "print one JSON object");
  cmd->add_flag("--table-feeds", a->table_feeds,
                "roughing at the tool table's feeds, not at feeds from the measured engagement (chip thinning)");
  cmd->add_option("--tools", a->tools, "tool table (default config/tools.yaml here, else the package's)");
  cmd->add_option("--presets", a->presets, "preset table (default config/presets.yaml here, else the package's)");
  cmd->add_option("--dialect", a->dialect, "linuxcnc or grbl")->capture_default_str();
  cmd->add_option("--machine", a->machine, "machine limits the programs are checked against");
  cmd->add_flag("--no-limits", a->no_limits, "write the programs without checking the machine's limits");
  add_work_offset_option(cmd, a->work_offset);
  cmd->callback([a] { run(*a); });
});

}  // namespace
}  // namespace rosmill::core::cli
