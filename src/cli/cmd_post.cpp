// rosmill post: toolpath.json -> G-code program in a controller's dialect, checked against the machine's limits
// (and, with --verify, by LinuxCNC's own interpreter).
#include <fstream>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "config_file.hpp"
#include "work_offset_option.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"

namespace rosmill::core::cli {
namespace {

struct PostArgs {
  std::string input, output, machine, map;
  gcode::PostOptions options;
  std::string coolant = "flood";
  double stock_top = NAN;
  bool verify = false, no_limits = false;
  WorkOffsetArgs work_offset;
};

gcode::Coolant parse_coolant(const std::string& s) {
  if (s == "flood") return gcode::Coolant::Flood;
  if (s == "mist") return gcode::Coolant::Mist;
  if (s == "off") return gcode::Coolant::Off;
  throw Error("--coolant", "expected flood, mist or off, got '" + s + "'");
}

void write_map(const std::string& path, const gcode::Program& p) {
  nlohmann::json lines = nlohmann::json::array();
  for (size_t i = 0; i < p.origin.size(); ++i) {
    const auto& o = p.origin[i];
    if (o.first_move < 0) continue;
    lines.push_back({i + 1, o.toolpath, o.pass, o.first_move, o.last_move});
  }
  std::ofstream out(path);
  out << nlohmann::json{{"format", "rosmill-gcode-map"},
                        {"columns", {"line", "toolpath", "pass", "first_move", "last_move"}},
                        {"lines", lines}}
             .dump()
      << '\n';
  if (!out) throw Error(path, "cannot write the line map");
}

void run(const PostArgs& a) {
  gcode::PostOptions o = a.options;
  o.coolant = parse_coolant(a.coolant);
  if (o.title.empty()) o.title = a.input;
  o.work_offset = work_offset_of(a.work_offset);
  const Job job = read_toolpath_file(a.input);
  post_for_machine(job, a.machine, o);
  gcode::ProgramChecks checks;
  checks.machine = machine_to_check(a.machine, a.no_limits);
  checks.limits.stock_top = a.stock_top;
  checks.rs274 = a.verify;
  const gcode::PreparedProgram prepared = gcode::prepare_program(job, o, checks);
  const gcode::Program& p = prepared.program;
  nlohmann::json report{{"output", a.output}, {"dialect", p.dialect}, {"lines", p.lines.size()},
                        {"motion_blocks", p.motion_blocks()}};
  if (o.arcs) {
    size_t moves = 0;
    for (const auto& tp : job) moves += tp.move_count();
    report["toolpath_moves"] = moves;
  }
  if (checks.machine) report["machine"] = machine_file(a.machine);
  if (prepared.rs274)
    report["rs274"] = {{"canon_moves", prepared.rs274->canon_moves},
                       {"max_deviation_mm", prepared.rs274->max_deviation}};
  gcode::write_program(a.output, p);
  if (!a.map.empty()) write_map(a.map, p);
  std::printf("%s\n", report.dump().c_str());
}

CommandRegistration reg([](CLI::App& app) {
  auto a = std::make_shared<PostArgs>();
  auto* cmd = app.add_subcommand("post", "write a toolpath file as a G-code program");
  cmd->add_option("TOOLPATH", a->input, "toolpath.json (rosmill plan -o)")->required();
  cmd->add_option("-o,--output", a->output, "the program to write (.ngc)")->required();
  cmd->add_option("--dialect", a->options.dialect, "linuxcnc or grbl")->capture_default_str();
  cmd->add_flag("--arcs", a->options.arcs, "fit G2/G3 arcs to runs of feed moves");
  cmd->add_option("--arc-tolerance", a->options.arc_tolerance, "mm")->capture_default_str();
  cmd->add_option("--decimals", a->options.decimals,
                  "digits after the point, 1 to 6 (default: enough to keep rounding within a tenth of the "
                  "toolpaths' tolerance, at least 3)")
      ->check(CLI::Range(1, 6));
  cmd->add_flag("--line-numbers", a->options.line_numbers, "write N words");
  cmd->add_option("--blend-tolerance", a->options.blend_tolerance, "G64 P (LinuxCNC), mm")->capture_default_str();
  cmd->add_option("--coolant", a->coolant, "flood, mist or off")->capture_default_str();
  cmd->add_option("--machine", a->machine,
                  "machine limits the program must keep (default config/machine.yaml here, else the package's)");
  cmd->add_flag("--no-limits", a->no_limits, "write the program without checking the machine's limits");
  cmd->add_option("--stock-top", a->stock_top, "stock top z for the rapid clearance check (default: highest cut)");
  cmd->add_flag("--verify", a->verify, "run LinuxCNC's rs274 on the program and compare its moves with the toolpath");
  cmd->add_option("--map", a->map, "write the line -> (toolpath, pass, move) map as JSON");
  add_work_offset_option(cmd, a->work_offset);
  cmd->callback([a] { run(*a); });
});

}  // namespace
}  // namespace rosmill::core::cli
