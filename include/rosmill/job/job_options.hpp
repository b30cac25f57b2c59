// A job's options from what runs it: the machine (its file's contents) and the request (`rosmill job`'s arguments,
// or a PlanJob goal with the planner node's parameters). The CLI and the ROS action both build them here, so the
// same job with the same request plans, times and writes the same programs from either.
#pragma once
#include <functional>
#include <optional>
#include <string>

#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/work_offset.hpp"
#include "rosmill/job/run_job.hpp"

namespace rosmill::core::job {

struct JobRequest {
  const ToolTable* tools = nullptr;
  const PresetTable* presets = nullptr;
  // The machine file's contents; none: no machine (times at the feeds alone, links at JobOptions' clearance).
  std::optional<gcode::MachineLimits> machine;
  // The programs are not checked against the machine's limits (nor its fixture position and max feed used); the
  // machine still times the moves and gives the clearance links keep over the stock.
  bool no_limits = false;
  bool verify_rs274 = false;  // run LinuxCNC's rs274 on every written program
  std::string out_dir;        // empty: no programs written
  bool per_operation = false;
  std::string dialect = "linuxcnc";
  bool table_feeds = false;   // roughing at the tool table's feeds, not at feeds from the measured engagement
  const Mesh* part = nullptr; // instead of the job's `part`
  // Where G54 is for the written programs; asked only when programs are written (a plan alone needs no
  // registered part). Empty, or returning none: the controller's G54 as it stands.
  std::function<std::optional<gcode::WorkOffset>()> work_offset;
};

// The options run_job takes (no callbacks set). Throws Error naming the field: an unknown dialect, or programs to
// write with neither a machine to check them against nor no_limits.
JobOptions job_options(const JobRequest& request);

}  // namespace rosmill::core::job
