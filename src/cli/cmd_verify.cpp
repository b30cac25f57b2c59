// rosmill verify DESIGN (PROGRAM.ngc|toolpath.json) [--stock box|x0,y0,z0,x1,y1,z1|STOCK.stl] [--resolution MM]
//   [--tool SPEC]... [--tools FILE] [--units U] [--tolerance MM] [--stepover MM] [--engagement-cell MM] [--json]
//   [--image deviation.png]
//   [--machine MACHINE.yaml [--on-table X,Y,Z]]
// Simulates the program on the stock and compares the result with the design (an STL or a cloud): the deepest
// gouge and the line that made it, the material left, the scallop, the area never reached; and the cutter's radial
// engagement along the program with the material removal rate (verify/engagement.hpp). With a trunnion machine
// (a machine file with `rotary:`), a 3+2 program is followed through its A/C indexing (verify/indexed.hpp): the
// design stands on the table at --on-table (where `rosmill job --json` says, workpiece_on_table). A toolpath file
// of a multi-axis finish (`rosmill plan --strategy five-axis|four-axis -o finish.json`) is followed with its tool
// axes (verify/multi_axis.hpp): the material left and any gouge over the whole of the design's surface; so is a
// program for the trunnion's tool-centre-point control (M428) with --machine, its A and C giving the tool axis.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "config_file.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/geometry/outline_from_above.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"
#include "rosmill/verify/deviation_image.hpp"
#include "rosmill/verify/engagement_json.hpp"
#include "rosmill/verify/gcode_reader.hpp"
#include "rosmill/verify/indexed.hpp"
#include "rosmill/verify/multi_axis.hpp"
#include "rosmill/verify/verify.hpp"

namespace rosmill::core::cli {
namespace {

using namespace rosmill::core::verify;
using namespace rosmill::core::stock;

struct VerifyArgs {
  std::string design, program, stock = "box", tools, units, image, machine, on_table;
  std::vector<std::string> tool;
  double resolution = 0.5, tolerance = 0.01, stepover = 0, engagement_cell = 0;
  bool json = false;
};

MachineProgram read_program(const VerifyArgs& a, bool rotary) {
  if (is_toolpath_path(a.program)) {
    if (!a.tool.empty()) throw Error("--tool", "a toolpath file names its own tools; --tool is for G-code programs");
    return program_from_job(read_toolpath_file(a.program));
  }
  // The tool table: --tools, else config/tools.yaml here or the package's (G-code calls tools by number).
  const std::string default_table = default_config("tools.yaml");
  const std::string table_path = !a.tools.empty()                        ? a.tools
                                 : std::filesystem::exists(default_table) ? default_table
                                                                          : "";
  std::unique_ptr<ToolTable> table;
  if (!table_path.empty()) table = std::make_unique<ToolTable>(read_tool_table(table_path));
  ToolSetup tools = tool_setup(a.tool, table.get());
  tools.rotary = rotary;
  return read_gcode(a.program, tools);
}

nlohmann::ordered_json to_json(const DeviationReport& r, const EngagementReport& e, double seconds) {
  using nlohmann::ordered_json;
  ordered_json j;
  j["max_gouge_mm"] = r.max_gouge_mm;
  j["gouge_at"] = r.gouged ? ordered_json::array({r.gouge_at.x(), r.gouge_at.y(), r.gouge_at.z()}) : ordered_json();
  j["gouge_line"] = r.gouged && r.gouge_source ? ordered_json(r.gouge_source) : ordered_json();
  j["max_rest_mm"] = r.max_rest_mm;
  j["mean_rest_mm"] = r.mean_rest_mm;
  j["scallop_mm"] = r.scallop_mm;
  j["unreached_area_mm2"] = r.unreached_area_mm2;
  j["cells"] = r.cells;
  j["engagement"] = engagement_json<nlohmann::ordered_json>(e);
  j["seconds"] = seconds;
  return j;
}

void print_text(const VerifyArgs& a, const MachineProgram& p, const VerifyResult& v, double seconds) {
  const DeviationReport& r = v.report;
  const GridSpec& g = v.grid.grid;
  const char* where = p.from_gcode ? "line" : "move";
  std::printf("verify %s with %s: %zu moves, %zu tools, %d x %d cells of %g mm\n", a.design.c_str(),
              a.program.c_str(), p.moves.size(), p.tools.size(), g.nx, g.ny, g.cell);
  if (r.gouged)
    std::printf("gouge      %.4f mm deep at (%.3f, %.3f, %.3f), %s %u; %zu cells deeper than %g mm\n", r.max_gouge_mm,
                r.gouge_at.x(), r.gouge_at.y(), r.gouge_at.z(), where, r.gouge_source, r.gouge_cells, a.tolerance);
  else
    std::printf("gouge      none deeper than %g mm\n", a.tolerance);
  std::printf("rest       max %.4f mm, mean %.4f mm\n", r.max_rest_mm, r.mean_rest_mm);
  if (r.scallop_theory_mm >= 0)
    std::printf("scallop    %.4f mm (theory %.4f mm at stepover %g mm)\n", r.scallop_mm, r.scallop_theory_mm,
                r.stepover_mm);
  else
    std::printf("scallop    %.4f mm (stepover unknown: --stepover gives the theory)\n", r.scallop_mm);
  std::printf("unreached  %.3f mm2\n", r.unreached_area_mm2);
  const EngagementReport& e = v.engagement;
  std::printf("engagement max %.1f deg, p95 %.1f deg, %.0f mm3/min removed while feeding (cell %g mm, within %.1f "
              "deg)\n", e.max_deg, e.p95_deg, e.mrr_mm3_per_min, e.cell_mm, e.tolerance_deg);
  if (r.rapid_cut_cells)
    std::printf("RAPID INTO MATERIAL: %zu cells, first at %s %u\n", r.rapid_cut_cells, where, r.first_rapid_cut_source);
  std::printf("seconds    %.3f (simulation %.3f)\n", seconds, v.simulation_seconds);
}

// "x,y,z" in mm.
Vec3 parse_point(const std::string& text, const std::string& where) {
  Vec3 p;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> p.x() >> c1 >> p.y() >> c2 >> p.z()) || c1 != ',' || c2 != ',' || !(in >> std::ws).eof() ||
      !p.allFinite())
    throw Error(where, "expected x,y,z (mm), got '" + text + "'");
  return p;
}

void print_indexed(const VerifyArgs& a, const IndexedVerifyResult& r) {
  if (a.json) {
    nlohmann::ordered_json runs = nlohmann::ordered_json::array();
    for (const IndexedRun& k : r.runs)
      runs.push_back({{"a_deg", k.a}, {"c_deg", k.c}, {"moves", k.moves}, {"first_line", k.first_source},
                      {"max_gouge_mm", k.report.gouged ? k.report.max_gouge_mm : 0.0}});
    nlohmann::ordered_json j;
    j["runs"] = runs;
    j["max_gouge_mm"] = r.max_gouge_mm;
    j["gouge_line"] = r.gouge_source ? nlohmann::ordered_json(r.gouge_source) : nlohmann::ordered_json();
    j["min_left_mm"] = r.min_left_mm;
    j["max_left_mm"] = r.max_left_mm;
    j["stock_mm3"] = r.stock_mm3;
    j["design_mm3"] = r.design_mm3;
    j["left_mm3"] = r.left_mm3;
    j["seconds"] = r.seconds;
    std::printf("%s\n", j.dump().c_str());
    return;
  }
  std::printf("verify %s with %s on the trunnion: %zu runs between indexings\n", a.design.c_str(), a.program.c_str(),
              r.runs.size());
  for (const IndexedRun& k : r.runs)
    std::printf("  A %9.4f C %9.4f from line %u: %zu moves, gouge %.4f mm\n", k.a, k.c, k.first_source, k.moves,
                k.report.gouged ? k.report.max_gouge_mm : 0.0);
  if (r.gouge_source)
    std::printf("gouge      %.4f mm deep, line %u\n", r.max_gouge_mm, r.gouge_source);
  else
    std::printf("gouge      none deeper than %g mm\n", a.tolerance);
  std::printf("left       %.4f to %.4f mm on the part seen from the runs' sides; %.0f mm3 over the design\n",
              r.min_left_mm, r.max_left_mm, r.left_mm3);
  std::printf("seconds    %.3f\n", r.seconds);
}

void print_multi_axis(const VerifyArgs& a, const MultiAxisVerifyResult& r) {
  if (a.json) {
    nlohmann::ordered_json j;
    j["multi_axis"] = true;
    j["moves"] = r.moves;
    j["samples"] = r.samples;
    j["area_mm2"] = r.area_mm2;
    j["max_gouge_mm"] = r.max_gouge_mm;
    j["gouge_at"] = r.gouge_source ? nlohmann::ordered_json::array({r.gouge_at.x(), r.gouge_at.y(), r.gouge_at.z()})
                                   : nlohmann::ordered_json();
    j["gouge_move"] = r.gouge_source ? nlohmann::ordered_json(r.gouge_source) : nlohmann::ordered_json();
    j["gouged_area_mm2"] = r.gouged_area_mm2;
    j["max_rest_mm"] = r.max_rest_mm;
    j["mean_rest_mm"] = r.mean_rest_mm;
    j["limit_mm"] = r.limit_mm;
    j["above_area_mm2"] = r.above_area_mm2;
    j["unreached_area_mm2"] = r.unreached_area_mm2;
    j["rapid_into_material_move"] =
        r.removal.collided() ? nlohmann::ordered_json(r.removal.first_rapid_source) : nlohmann::ordered_json();
    j["removed_mm3"] = r.removal.removed_mm3;
    j["stock_mm3"] = r.stock_mm3;
    j["left_mm3"] = r.left_mm3;
    j["seconds"] = r.seconds;
    std::printf("%s\n", j.dump().c_str());
    return;
  }
  std::printf(
      "verify %s with %s (multi-axis, the tool axis at every move): %zu moves, %zu samples of the design's "
      "%.1f mm2\n",
      a.design.c_str(), a.program.c_str(), r.moves, r.samples, r.area_mm2);
  if (r.gouge_source)
    std::printf("gouge      %.4f mm deep at (%.3f, %.3f, %.3f), move %u; %.2f mm2 deeper than %g mm\n", r.max_gouge_mm,
                r.gouge_at.x(), r.gouge_at.y(), r.gouge_at.z(), r.gouge_source, r.gouged_area_mm2, a.tolerance);
  else
    std::printf("gouge      none deeper than %g mm\n", a.tolerance);
  std::printf("rest       max %.4f mm, mean %.4f mm over the surface\n", r.max_rest_mm, r.mean_rest_mm);
  std::printf(
      "above      %.2f mm2 left above %.4f mm (the tolerance%s), %.2f mm2 of it where no tool came within 1 mm\n",
      r.above_area_mm2, r.limit_mm, a.stepover > 0 || r.limit_mm > a.tolerance ? " and the scallop" : "",
      r.unreached_area_mm2);
  if (r.removal.collided()) std::printf("RAPID INTO MATERIAL: first at move %u\n", r.removal.first_rapid_source);
  std::printf("removed    %.0f mm3; %.0f mm3 of stock left\n", r.removal.removed_mm3, r.stock_mm3);
  std::printf("seconds    %.3f\n", r.seconds);
}

// The moves of a G-code program made under tool-centre-point kinematics, with the tool axis A and C give them on
// the trunnion; none when it has no such move. A program that also cuts in 3+2 runs is refused: each part would be
// in its own frame.
std::optional<stock::MultiAxisProgram> tool_centre_point_program(const MachineProgram& p, const machine::Trunnion& t) {
  if (std::none_of(p.moves.begin(), p.moves.end(), [](const CanonMove& m) { return m.tool_centre_point; }))
    return std::nullopt;
  stock::MultiAxisProgram out;
  out.tools = p.tools;
  for (const CanonMove& m : p.moves) {
    const std::string where = "line " + std::to_string(m.source);
    if (!m.tool_centre_point)
      throw Error(where,
                  "cuts outside tool-centre-point kinematics in a program that also cuts under it (M428): "
                  "verify its 3+2 runs and its simultaneous moves as programs of their own");
    if (m.is_arc()) throw Error(where, "an arc under tool-centre-point kinematics is not followed by the verifier");
    if (m.known_rotary != 3) throw Error(where, "A and C are not known here: the tool axis is not");
    stock::AxisMove am;
    am.from = m.from;
    am.to = m.to;
    am.axis_from = t.tool_axis(m.a_from, m.c_from);
    am.axis_to = t.tool_axis(m.a_to, m.c_to);
    am.tool = m.tool;
    am.rapid = m.rapid;
    am.source = m.source;
    out.moves.push_back(am);
  }
  return out;
}

// A toolpath file whose passes carry a tool axis per move: its job, else none.
std::optional<std::vector<Toolpath>> multi_axis_toolpaths(const VerifyArgs& a) {
  if (!is_toolpath_path(a.program)) return std::nullopt;
  std::vector<Toolpath> job = read_toolpath_file(a.program);
  if (std::none_of(job.begin(), job.end(), [](const Toolpath& tp) { return tp.multi_axis(); })) return std::nullopt;
  return job;
}

void run(const VerifyArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  VerifyOptions o;
  o.resolution = a.resolution;
  o.compare.tolerance = a.tolerance;
  o.compare.stepover = a.stepover;
  o.measure_engagement = true;
  o.engagement.cell = a.engagement_cell;
  if (!(a.tolerance >= 0)) throw Error("--tolerance", "must be zero or more mm");
  if (!(a.stepover >= 0)) throw Error("--stepover", "must be zero or more mm");
  std::optional<machine::Trunnion> trunnion;
  if (!a.machine.empty()) {
    trunnion = gcode::load_machine_limits(a.machine).trunnion;
    if (!trunnion) throw Error("--machine " + a.machine, "has no rotary axes: verify a 3-axis program without it");
  } else if (!a.on_table.empty()) {
    throw Error("--on-table", "is for a trunnion machine: give --machine too");
  }
  const std::optional<std::vector<Toolpath>> multi_axis = multi_axis_toolpaths(a);
  if (multi_axis && trunnion)
    throw Error("--machine", "a multi-axis toolpath file is in the workpiece frame: verify it without --machine");
  if (multi_axis && !a.tool.empty())
    throw Error("--tool", "a toolpath file names its own tools; --tool is for G-code programs");
  const MachineProgram program = multi_axis ? MachineProgram{} : read_program(a, trunnion.has_value());
  // A program for tool-centre-point kinematics (M428): its X Y Z are the tip in the design's frame (G54 where the
  // design's origin stands), its A and C the tool axis.
  const std::optional<stock::MultiAxisProgram> tool_centre_point =
      trunnion ? tool_centre_point_program(program, *trunnion) : std::nullopt;
  if (trunnion && !tool_centre_point && a.on_table.empty())
    throw Error("--on-table",
                "missing: where the design stands on the table at A = C = 0, x,y,z (mm; `rosmill job "
                "--json` gives it as workpiece_on_table)");

  Mesh stock_mesh;
  StockSpec stock;
  if (a.stock == "box" || a.stock.find(',') != std::string::npos) {
    stock = StockSpec::parse_box(a.stock);
  } else {
    StlReadOptions so;
    if (!a.units.empty()) so.units = parse_units(a.units, "--units");
    stock_mesh = read_stl(a.stock, so);
    stock.kind = StockSpec::Kind::Mesh;
    stock.mesh = &stock_mesh;
  }

  if (multi_axis || tool_centre_point) {
    if (is_cloud_file(a.design)) throw Error(a.design, "a multi-axis program is verified against an STL design");
    if (!a.image.empty()) throw Error("--image", "the deviation map is drawn for 3-axis programs only");
    if (tool_centre_point && !a.on_table.empty())
      throw Error("--on-table", "a program for tool-centre-point kinematics is in the design's frame: no --on-table");
    StlReadOptions so;
    if (!a.units.empty()) so.units = parse_units(a.units, "--units");
    const double stepover = a.stepover > 0 ? a.stepover : multi_axis ? multi_axis->back().tool.stepover : 0.0;
    const MultiAxisVerifyResult r = verify_multi_axis(
        read_stl(a.design, so), multi_axis ? multi_axis_program_from_job(*multi_axis) : *tool_centre_point, stock, o,
        stepover);
    print_multi_axis(a, r);
    return;
  }
  if (trunnion) {
    if (is_cloud_file(a.design)) throw Error(a.design, "a 3+2 program is verified against an STL design");
    StlReadOptions so;
    if (!a.units.empty()) so.units = parse_units(a.units, "--units");
    const Vec3 at = parse_point(a.on_table, "--on-table");
    const Placement on_table{"table", kWorkpieceFrame, Eigen::Isometry3d(Eigen::Translation3d(at))};
    const IndexedVerifyResult r = verify_indexed(read_stl(a.design, so), program, *trunnion, on_table, stock, o);
    print_indexed(a, r);
    return;
  }
  VerifyResult v;
  std::vector<Contour> outline;  // a cloud design's: the picture draws the cells it covers
  if (is_cloud_file(a.design)) {
    CloudReadOptions co;
    if (!a.units.empty()) co.units = parse_units(a.units, "--units");
    v = verify_program(read_cloud(a.design, co), program, stock, o);
  } else {
    StlReadOptions so;
    if (!a.units.empty()) so.units = parse_units(a.units, "--units");
    const Mesh design = read_stl(a.design, so);
    v = verify_program(design, program, stock, o);
    if (!a.image.empty()) outline = outline_from_above(design);
  }
  if (!a.image.empty()) {
    const picture::MapCaption caption{"deviation map", std::filesystem::path(a.design).filename().string(),
                                      "program " + std::filesystem::path(a.program).filename().string(), ""};
    write_deviation_png(a.image, v.grid, v.report, outline, caption);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (a.json) std::printf("%s\n", to_json(v.report, v.engagement, seconds).dump().c_str());
  else print_text(a, program, v, seconds);
}

CommandRegistration reg([](CLI::App& app) {
  auto a = std::make_shared<VerifyArgs>();
  auto* cmd = app.add_subcommand("verify", "simulate a program on the stock and compare it with the design");
  cmd->add_option("DESIGN", a->design, "the part: STL, or a cloud (PCD, PLY)")->required();
  cmd->add_option("PROGRAM", a->program, "G-code (.ngc, ...) or toolpath.json (rosmill plan -o)")->required();
  cmd->add_option("--stock", a->stock,
                  "box (the design's bounds), x0,y0,z0,x1,y1,z1 (mm), or an STL of the stock")->capture_default_str();
  cmd->add_option("--resolution", a->resolution, "cell size, mm")->capture_default_str();
  cmd->add_option("--tool", a->tool,
                  "G-code tools: N=CUTTER defines tool N (ball:D, flat:D, bull:D:r); CUTTER or N is the tool in the "
                  "spindle at the start (repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--tools", a->tools, "tool table (default config/tools.yaml here, else the package's)");
  cmd->add_option("--units", a->units, "units of the STL and cloud files: mm, inch, m (STL default mm, clouds m)");
  cmd->add_option("--tolerance", a->tolerance, "deviation that still counts as on the design, mm")
      ->capture_default_str();
  cmd->add_option("--stepover", a->stepover, "stepover of the finishing passes for the scallop theory, mm "
                                             "(toolpath files carry theirs)");
  cmd->add_option("--engagement-cell", a->engagement_cell,
                  "cell of the engagement measurement, mm (default 0.1, or R/40 of the smallest cutter if finer)");
  cmd->add_flag("--json", a->json, "print one JSON object");
  cmd->add_option("--image", a->image, "write the deviation map as a PNG picture");
  cmd->add_option("--machine", a->machine,
                  "a trunnion machine file (rotary:): follow a 3+2 program through its A/C indexing, or a program for "
                  "tool-centre-point control (M428) with its tool axes");
  cmd->add_option("--on-table", a->on_table,
                  "with --machine: x,y,z (mm) where the design's origin stands on the table at A = C = 0");
  cmd->callback([a] { run(*a); });
});

}  // namespace
}  // namespace rosmill::core::cli
