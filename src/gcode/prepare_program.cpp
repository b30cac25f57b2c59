#include "rosmill/gcode/prepare_program.hpp"

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"

namespace rosmill::core::gcode {
namespace {

// Every tool a program loads by its number in the controller's tool table: a tool without one would be written
// T0 M6, which empties LinuxCNC's spindle, and G43 H0, no length offset; two cutters under one number would cut
// with whichever the controller holds there.
void require_tool_numbers(const Job& job) {
  for (size_t t = 0; t < job.size(); ++t) {
    const Tool& tool = job[t].tool;
    const std::string which = "toolpath " + std::to_string(t + 1) + " (" + job[t].strategy + ")";
    if (tool.id == kNoToolNumber)
      throw Error(which, "its tool '" + (tool.name.empty() ? inline_tool_spec(tool.cutter, kNoToolNumber) : tool.name) +
                             "' has no number in the controller's tool table: give it as " +
                             inline_tool_spec(tool.cutter, kNoToolNumber) +
                             "@N (N: its tool number), or name a tool of the tool table");
    for (size_t u = 0; u < t; ++u)
      if (job[u].tool.id == tool.id && !same_cutter(job[u].tool.cutter, tool.cutter))
        throw Error(which, "tool T" + std::to_string(tool.id) + " is another cutter in toolpath " +
                               std::to_string(u + 1) + ": one number, one tool");
  }
}

}  // namespace

PostOptions with_tool_centre_point(PostOptions o, const MachineLimits& m, const std::string& where) {
  const std::shared_ptr<const machine::Machine> kind = m.machine();
  if (!kind->simultaneous() || !kind->trunnion())
    throw Error(where, "the toolpaths carry a tool axis at every move (five-axis): the machine '" + m.name + "' (a " +
                           kind->kind() +
                           ") has no trunnion with tool-centre-point control (rotary.mode: "
                           "tool-centre-point; config/machine_xyzac_tcp.yaml has)");
  o.trunnion = m.trunnion;
  o.index_safe_z = m.trunnion->safe_z;
  o.axis_velocity = m.trajectory.max_velocity;
  o.max_feed = m.max_feed;
  o.program_origin = m.work_offset.origin;
  return o;
}

PreparedProgram prepare_program(const Job& job, const PostOptions& post_options, const ProgramChecks& checks) {
  if (job.empty()) throw Error("job", "has no toolpath");
  require_tool_numbers(job);
  PreparedProgram p;
  p.program = post(job, post_options);
  if (checks.machine) {
    require_within_limits(p.program.lines, *checks.machine, checks.limits);
    p.limits_checked = true;
  }
  if (checks.rs274) {
    VerifyReport report = compare_with_job(p.program, job, run_rs274(p.program.lines), post_options.arc_tolerance);
    if (!report.ok) throw Error("rs274 verification", report.problem);
    p.rs274 = std::move(report);
  }
  return p;
}

void check_program(const std::vector<std::string>& lines, const ProgramChecks& checks, const std::string& source) {
  if (lines.empty()) throw Error(source, "the program is empty");
  if (checks.machine) require_within_limits(lines, *checks.machine, checks.limits);
  if (checks.rs274) {
    const Rs274Result r = run_rs274(lines);
    if (!r.ok)
      throw Error(source + (r.error_line ? " line " + std::to_string(r.error_line) : ""),
                  "LinuxCNC's interpreter (rs274) refuses the program: " + r.error);
  }
}

}  // namespace rosmill::core::gcode
