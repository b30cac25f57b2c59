// The demo-style jobs, before and after planning knew the stock, side by side in one run: per operation the
// planning seconds, the air-cutting share, the cutting length and the estimated time (LinuxCNC sim's
// accelerations, config/machine.yaml), and the job's totals.
//   BEFORE: today's behaviour before this change: the box around the part, every operation planned alone (the rest
//           operation runs as a full finish).
//   AFTER:  the job's own stock (a casting or a scan), every operation planned on what the ones before left, the
//           last one rest machining.
// Jobs: config/jobs/rest_pocket.yaml (pocket from a casting: rough 10 flat, finish 6 ball, rest 3 ball) and
// config/jobs/scanned_dome.yaml with a rest operation with the 3 mm ball added. Usage: bench_job [threads]
#include <cstdio>
#include <cstdlib>
#include <string>

#include <tbb/global_control.h>

#include "cpu_time.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/job/run_job.hpp"

using namespace rosmill::core;
using namespace rosmill::core::job;

namespace {

void print(const char* label, const JobReport& r) {
  double plan = 0;
  for (const OperationReport& op : r.operations) {
    std::printf("  %-6s %-10s %-9s %-8s plan %6.2f s  air %5.1f %%  cutting %8.0f mm  time %7.0f s%s\n", label,
                op.name.c_str(), op.strategy.c_str(), op.tool.c_str(), op.plan_seconds, 100 * op.air_cut_share,
                op.cutting_mm, op.time_s, op.rest ? "  (rest)" : "");
    plan += op.plan_seconds;
  }
  std::printf("  %-6s %-29s plan %6.2f s  air %5.1f %%  removed %7.0f mm3      time %7.0f s\n", label, "job", plan,
              100 * r.air_cut_share, r.removed_mm3, r.time_s);
}

void compare(const std::string& name, const JobSpec& after, const JobOptions& options) {
  JobSpec before = after;
  before.stock = StockSpec{};  // the box, 5 mm over the part's bounds
  for (OperationSpec& op : before.operations) op.rest = false;
  JobOptions alone = options;
  alone.plan_on_stock = false;
  std::printf("== %s\n", name.c_str());
  const double cpu0 = cpu_seconds_used();
  print("BEFORE", run_job(before, alone));
  print("AFTER", run_job(after, options));
  std::printf("  (cpu %.1f s for both)\n", cpu_seconds_used() - cpu0);
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const std::string config = std::string(ROSMILL_SOURCE_DIR) + "/config/";
  const ToolTable tools = read_tool_table(config + "tools.yaml");
  const gcode::MachineLimits machine = gcode::load_machine_limits(config + "machine.yaml");
  JobOptions options;
  options.tools = &tools;
  options.max_acceleration = machine.max_acceleration;
  options.link_clearance = machine.clearance_over_stock;
  compare("rest_pocket (casting)", read_job(config + "jobs/rest_pocket.yaml"), options);
  JobSpec dome = read_job(config + "jobs/scanned_dome.yaml");
  OperationSpec rest = dome.operations.back();
  rest.name = "rest";
  rest.tool = "3";  // the 3 mm ball of the tool table
  rest.stepover = 0.5;
  rest.rest = true;
  dome.operations.push_back(rest);
  compare("scanned_dome + rest 3 mm ball (scan)", dome, options);
  return 0;
}
