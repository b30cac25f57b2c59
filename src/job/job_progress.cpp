#include "rosmill/job/job_progress.hpp"

#include <algorithm>
#include <memory>
#include <vector>

namespace rosmill::core::job {

void report_progress(JobOptions& options, const JobSpec& spec, std::function<bool(const JobProgress&)> report) {
  // The operations as the job will run them: the file's, until chosen setups make them known.
  auto ops = std::make_shared<std::vector<OperationSpec>>(spec.operations);
  options.operations_known = [ops](const std::vector<OperationSpec>& known) { *ops = known; };
  options.progress = [ops, report = std::move(report)](size_t op, double fraction) {
    JobProgress p;
    p.operation = op;
    p.operations = ops->size();
    if (op < ops->size()) p.name = (*ops)[op].name, p.setup = (*ops)[op].setup;
    p.operation_fraction = std::clamp(fraction, 0.0, 1.0);
    p.fraction = std::min(1.0, (double(op) + p.operation_fraction) / double(std::max<size_t>(ops->size(), 1)));
    return report(p);
  };
}

}  // namespace rosmill::core::job
