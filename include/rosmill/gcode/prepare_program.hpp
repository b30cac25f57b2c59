// The one program pipeline: every G-code program rosmill writes or sends passes here, whichever way it came
// (`rosmill plan -o prog.ngc`, `rosmill post`, `rosmill send`, the ROS bridge). A toolpath job is posted in the
// controller's dialect (arcs fitted on request), then checked against the machine's limits, then optionally by
// LinuxCNC's own interpreter (rs274), whose canonical moves must be the job's moves. A program that fails a check
// is refused with the line and the limit; nothing is written before every check has passed.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/gcode/rs274_check.hpp"

namespace rosmill::core::gcode {

// What a program is checked against. Without a machine the limits are not checked: only an explicit opt-out
// (`--no-limits`) leaves it empty.
struct ProgramChecks {
  std::optional<MachineLimits> machine;
  LimitCheckOptions limits;
  bool rs274 = false;  // run LinuxCNC's interpreter on the program
};

struct PreparedProgram {
  Program program;
  bool limits_checked = false;
  std::optional<VerifyReport> rs274;  // set when checks.rs274
};

// The post's options for multi-axis toolpaths on `machine`: its trunnion with tool-centre-point control, its safe Z,
// its axes' speeds and its G54 origin (post.hpp). Throws Error naming the machine when it has no such trunnion.
PostOptions with_tool_centre_point(PostOptions options, const MachineLimits& machine, const std::string& where);

// Posts `job` and runs the checks; throws Error naming the program line and what it breaks.
PreparedProgram prepare_program(const Job& job, const PostOptions& post, const ProgramChecks& checks);

// The checks for a program that exists only as text (a file to send): the limits, and rs274's acceptance (there
// is no job to compare its moves with). `source` names the program in errors.
void check_program(const std::vector<std::string>& lines, const ProgramChecks& checks, const std::string& source);

}  // namespace rosmill::core::gcode
