// Cycle time: rosmill's estimate beside LinuxCNC's own run time. Each program runs to its end on the headless
// simulator (scripts/linuxcnc-sim, the stock sim/axis_mm machine, or with --xyzac the trunnion table) through the
// linuxcncrsh driver; the simulator's machine clock (servo periods at their nominal length) times it from the
// program's start to its end, and its motion clock the periods in which the planner had motion to run.
// Only one LinuxCNC runs per machine: run it under `flock /tmp/rosmill-linuxcnc.lock`.
// Usage: bench_cycle_time [--machine FILE] [--xyzac] [--estimate-only] PROGRAM.ngc...
//   prints per program: lines, estimate s, simulator s (start to end, within a second), simulator motion s,
//   estimate / simulator motion.

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "../test/core/linuxcnc_simulator.hpp"
#include "rosmill/control/program_run.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/cycle_time.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/post.hpp"

using namespace rosmill::core;

int main(int argc, char** argv) {
  std::string machine_file = ROSMILL_SOURCE_DIR "/config/machine.yaml", sim_machine;
  std::vector<std::string> programs;
  bool estimate_only = false;
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--machine") && k + 1 < argc) machine_file = argv[++k];
    else if (!std::strcmp(argv[k], "--estimate-only")) estimate_only = true;
    else if (!std::strcmp(argv[k], "--xyzac")) sim_machine = "xyzac";
    else programs.push_back(argv[k]);
  }
  if (programs.empty()) {  // bench/run runs every bench without arguments: this one needs programs and an hour
    std::printf("bench_cycle_time [--machine FILE] [--xyzac] [--estimate-only] PROGRAM.ngc...; every example job: "
                "bench/cycle_time_jobs\n");
    return 0;
  }
  try {
    const gcode::MachineLimits machine = gcode::load_machine_limits(machine_file);
    if (estimate_only) {
      for (const std::string& path : programs) {
        const gcode::CycleTime t = gcode::estimate_cycle_time(gcode::read_program_lines(path), machine.trajectory, path);
        std::printf("%-60s %10.1f s (moving %.1f s, %zu segments, %zu stops)\n", path.c_str(), t.seconds,
                    t.motion_seconds, t.segments, t.stops);
      }
      return 0;
    }
    sim_test::Simulator sim(sim_machine);
    if (!sim.running()) throw std::runtime_error(sim.failure());
    auto c = sim.controller();
    c->connect();
    std::printf("%-60s %7s %10s %10s %10s %7s\n", "program", "lines", "estimate s", "sim s", "motion s", "ratio");
    for (const std::string& path : programs) {
      const std::vector<std::string> lines = gcode::read_program_lines(path);
      const double estimate = gcode::estimate_cycle_time(lines, machine.trajectory, path).seconds;
      const auto t = sim.run_timed(*c, lines, 3.0);
      std::printf("%-60s %7zu %10.1f %10.1f %10.1f %7.3f\n", path.c_str(),
                  lines.size(), estimate, t.all, t.motion, estimate / t.motion);
      std::fflush(stdout);
    }
    c->disconnect();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_cycle_time: %s\n", e.what());
    return 1;
  }
  return 0;
}
