// The demo-style jobs, before and after planning knew the stock, side by side in one run: per operation the
// planning seconds, the air-cutting share, the cutting length and the estimated time (LinuxCNC sim's
// accelerations, config/machine.yaml), and the job's totals.
//   BEFORE: today's behaviour before this change: the box around the part, every operation planned alone (the rest
//           operation runs as a full finish).
//   AFTER:  the job's own stock (a casting or a scan), every operation planned on what the ones before left, the
//           last one rest machining.
// Jobs: config/jobs/rest_pocket.yaml (pocket from a casting: rough 10 flat, finish 6 ball, rest 3 ball) and
// config/jobs/scanned_dome.yaml with a rest operation with the 3 mm ball added.
// Then the multi-setup job config/jobs/pocket_sides.yaml (the pocket casting, top and four sides in a vise): per
// setup the planning seconds, the estimated machining time and the air-cutting share, the job's totals, and the
// whole job as a user meets it: `rosmill job ... -o DIR` in a fresh process (programs checked, setup sheet
// written; best of 3). Then the two-sided block config/jobs/slotted_block_xyzac.yaml twice: 3+2 on LinuxCNC's
// trunnion simulator (config/machine_xyzac.yaml: one clamping, one program, the indexing's retract, turn and way
// down in the time) beside re-clamping on the 3-axis mill (config/machine.yaml: a program a setup; the person's
// re-clamping is not in the time). Usage: bench_job [threads]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
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

void multi_setup(const std::string& file, const JobOptions& options, const std::string& machine_file = "") {
  std::printf("== %s%s\n", file.c_str(), machine_file.empty() ? "" : (" on " + machine_file).c_str());
  const double cpu0 = cpu_seconds_used();
  const JobReport r = run_job(read_job(file), options);
  double plan_all = 0;
  for (size_t k = 0; k < r.setups.size(); ++k) {
    const SetupReport& s = r.setups[k];
    double plan = 0, feed = 0, air = 0;
    for (size_t op : s.operations) {
      plan += r.operations[op].plan_seconds + r.operations[op].remove_seconds;
      feed += r.operations[op].cutting_mm;
      air += r.operations[op].air_feed_mm;
    }
    plan_all += plan;
    std::printf("  setup %zu %-6s %s down  %zu operations  plan %5.2f s  time %6.0f s  air %5.1f %%  finishes %5.0f mm2",
                k + 1, s.name.c_str(), s.face_down.c_str(), s.operations.size(), plan, s.time_s,
                feed > 0 ? 100 * air / feed : 0.0, s.finished_area);
    if (s.index) std::printf("  (indexing A %.0f C %.0f: %.1f s)", s.index->a, s.index->c, s.indexing_s);
    std::printf("\n");
  }
  std::printf("  job: %zu setups, plan %.2f s (cpu %.2f s), time %.0f s, air %.1f %%, removed %.0f mm3, left %.0f mm3\n",
              r.setups.size(), plan_all, cpu_seconds_used() - cpu0, r.time_s, 100 * r.air_cut_share, r.removed_mm3,
              r.left_mm3);
  const std::string out = "/tmp/rosmill_bench_job_setups";
  const std::string command = std::string(ROSMILL_CLI) + " job '" + file + "' -o " + out +
                              (machine_file.empty() ? "" : " --machine '" + machine_file + "'") + " > /dev/null";
  double best = 1e9;
  for (int i = 0; i < 3; ++i) {
    const auto start = std::chrono::steady_clock::now();
    if (std::system(command.c_str()) != 0) {
      std::printf("  rosmill job failed\n");
      return;
    }
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::printf("  rosmill job -o (a fresh process: %zu program(s) checked%s, the setup sheet): %.2f s\n",
              r.indexed ? size_t(1) : r.setups.size(), r.indexed ? " and read back through the indexing" : "", best);
  std::filesystem::remove_all(out);
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
  options.trajectory = machine.trajectory;
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
  JobOptions checked = options;
  checked.checks.machine = machine;
  multi_setup(config + "jobs/pocket_sides.yaml", checked);
  // The two-sided block: 3+2 on the trunnion beside re-clamping on the 3-axis mill.
  for (const char* m : {"machine_xyzac.yaml", "machine.yaml"}) {
    JobOptions o = options;
    o.checks.machine = gcode::load_machine_limits(config + m);
    o.trajectory = o.checks.machine->trajectory;
    multi_setup(config + "jobs/slotted_block_xyzac.yaml", o, config + m);
  }
  return 0;
}
