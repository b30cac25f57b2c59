#include "rosmill/gcode/prepare_program.hpp"

#include "rosmill/error.hpp"

namespace rosmill::core::gcode {

PreparedProgram prepare_program(const Job& job, const PostOptions& post_options, const ProgramChecks& checks) {
  if (job.empty()) throw Error("job", "has no toolpath");
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
