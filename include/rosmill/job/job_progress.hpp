// The whole job's progress from run_job's per-operation hooks: which operation of how many, its name and setup,
// and the fraction of the job done. One source for what the PlanJob action sends as feedback and for the command
// line's progress bar.
#pragma once
#include <functional>
#include <string>

#include "rosmill/job/run_job.hpp"

namespace rosmill::core::job {

struct JobProgress {
  size_t operation = 0, operations = 0;
  std::string name, setup;         // the operation's
  double operation_fraction = 0;   // of this operation, 0..1
  double fraction = 0;             // of the job: (operation + operation_fraction) / operations
};

// Sets `options.progress` and `options.operations_known` (for a job of `spec`) so that `report` is called with the
// job's progress; its answer is progress's (false cancels the job).
void report_progress(JobOptions& options, const JobSpec& spec, std::function<bool(const JobProgress&)> report);

}  // namespace rosmill::core::job
