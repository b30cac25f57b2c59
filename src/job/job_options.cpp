#include "rosmill/job/job_options.hpp"

#include "rosmill/error.hpp"
#include "rosmill/gcode/dialect.hpp"

namespace rosmill::core::job {
namespace {

// The machine's part: its limits check the programs (and place the fixtures, cap the feeds) unless no_limits; its
// trajectory planner times the moves and its clearance over the stock is what links keep over it either way.
void take_machine(const JobRequest& request, JobOptions& o) {
  if (!request.machine) {
    if (!request.out_dir.empty() && !request.no_limits)
      throw Error("output folder", "the programs are checked against the machine's limits, and no machine is "
                                   "given: give its file (rosmill job --machine, the planner's parameter machine) "
                                   "or ask for no limits (--no-limits, no_limits)");
    return;
  }
  const gcode::MachineLimits& m = *request.machine;
  if (!request.no_limits) o.checks.machine = m;
  o.trajectory = m.trajectory;
  if (m.clearance_over_stock > 0) o.link_clearance = m.clearance_over_stock;
}

}  // namespace

JobOptions job_options(const JobRequest& request) {
  gcode::find_dialect(request.dialect);  // an unknown name fails now, not at the first program
  JobOptions o;
  o.tools = request.tools;
  o.presets = request.presets;
  o.out_dir = request.out_dir;
  o.per_operation = request.per_operation;
  o.dialect = request.dialect;
  o.feeds_from_engagement = !request.table_feeds;
  o.part = request.part;
  o.checks.rs274 = request.verify_rs274;
  take_machine(request, o);
  if (!request.out_dir.empty() && request.work_offset) o.work_offset = request.work_offset();
  return o;
}

}  // namespace rosmill::core::job
