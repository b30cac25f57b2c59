// A headless LinuxCNC simulator for a test (scripts/linuxcnc-sim), stopped by its PID whatever the test does.
#pragma once
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "rosmill/control/linuxcnc.hpp"
#include "rosmill/control/program_run.hpp"

namespace sim_test {

using rosmill::core::control::ControllerOptions;
using rosmill::core::control::LinuxcncController;

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// One headless LinuxCNC for the test's lifetime: the stock sim/axis_mm machine, or with `machine` "xyzac" the
// five-axis trunnion table (scripts/linuxcnc-sim).
class Simulator {
 public:
  explicit Simulator(const std::string& machine = "") : table_(machine == "xyzac" ? "xyzac-trt.tbl" : "sim_mm.tbl") {
    char tmpl[] = "/tmp/rosmill-linuxcnc-test-XXXXXX";
    if (!::mkdtemp(tmpl)) throw std::runtime_error("mkdtemp failed");
    root_ = tmpl;
    ::chmod(root_.c_str(), 0755);  // the simulator runs as another user and reads the programs from here
    programs_ = root_ + "/programs";
    ::mkdir(programs_.c_str(), 0755);
    const std::string out = root_ + "/start.out";
    const std::string cmd = "ROSMILL_SIM_MACHINE=" + machine + " ROSMILL_SIM_OWNER=" + std::to_string(::getpid()) +
                            " " ROSMILL_SOURCE_DIR
                            "/scripts/linuxcnc-sim start " + root_ + "/sim >" + out + " 2>&1";
    const int rc = std::system(cmd.c_str());
    std::istringstream reply(slurp(out));
    if (rc != 0 || !(reply >> port_)) {
      failure_ = "scripts/linuxcnc-sim start failed: " + slurp(out);
      port_ = 0;
    }
  }
  ~Simulator() {
    // Whenever the script left a PID file (also when start failed half-way), the simulator is stopped by PID.
    if (std::filesystem::exists(root_ + "/sim/sim.pid")) {
      const std::string cmd = ROSMILL_SOURCE_DIR "/scripts/linuxcnc-sim stop " + root_ + "/sim >/dev/null 2>&1";
      if (std::system(cmd.c_str()) != 0) std::fprintf(stderr, "linuxcnc-sim stop failed for %s\n", root_.c_str());
    }
    std::error_code ec;
    std::filesystem::remove_all(root_, ec);
  }
  bool running() const { return port_ > 0; }
  const std::string& failure() const { return failure_; }

  std::unique_ptr<LinuxcncController> controller() const {
    ControllerOptions o;
    o.program_dir = programs_;
    o.program_name = "test.ngc";
    return std::make_unique<LinuxcncController>("127.0.0.1", port_, o);
  }

  // The simulator's machine time in seconds (scripts/linuxcnc-sim clock): servo periods counted at their nominal
  // length, so a loaded computer that runs the servo thread late does not stretch it. `motion` counts only the
  // periods in which the trajectory planner had motion to run; `first_motion` and `last_motion` are the clock's
  // value at the first motion since arm() and at the last motion so far.
  struct Clock {
    double all = NAN, motion = NAN, first_motion = NAN, last_motion = NAN;
  };
  Clock clock() const {
    const std::string out = root_ + "/clock.out";
    const std::string cmd = ROSMILL_SOURCE_DIR "/scripts/linuxcnc-sim clock " + root_ + "/sim >" + out + " 2>&1";
    Clock c;
    if (std::system(cmd.c_str()) != 0 ||
        !(std::istringstream(slurp(out)) >> c.all >> c.motion >> c.first_motion >> c.last_motion))
      throw std::runtime_error("scripts/linuxcnc-sim clock failed: " + slurp(out));
    return c;
  }
  // The next motion is a run's first (scripts/linuxcnc-sim arm); the machine must be at rest.
  void arm() const {
    const std::string cmd = ROSMILL_SOURCE_DIR "/scripts/linuxcnc-sim arm " + root_ + "/sim >/dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0) throw std::runtime_error("scripts/linuxcnc-sim arm failed");
  }

  // Runs `program` to its end on controller `c` and returns the machine time it took: `all` from its first motion
  // to its last (the latches of scripts/linuxcnc-sim: what happens before the first motion, the program's upload
  // and opening, and the reading of the status after the last take wall time that a loaded computer stretches;
  // the machine time between is the program's own), `motion` the periods in which the planner had motion to run.
  // linuxcncrsh may report a program idle while the planner still runs it, so the end is when the motion clock
  // has stood still for `settle_s` of machine time (not wall time: on a loaded computer one reading of the clocks
  // can take longer than that, and a wall-clock wait would end while the program still moves).
  struct Run {
    double all = NAN, motion = NAN;
  };
  // `progress` sees every status polled during the run (the controller's position on the way).
  Run run_timed(rosmill::core::control::Controller& c, const std::vector<std::string>& program, double settle_s = 2.0,
                const rosmill::core::control::Progress& progress = {}) const {
    arm();
    const Clock before = clock();
    const auto s =
        rosmill::core::control::run_to_end(c, program, rosmill::core::control::SendOptions{}, progress, 120.0);
    if (s.state != rosmill::core::control::RunState::Finished)
      throw std::runtime_error("the program did not run to its end: " + s.error);
    Clock after = clock();
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    for (Clock moved = after; after.all - moved.all < settle_s;) {
      if (std::chrono::steady_clock::now() > give_up)
        throw std::runtime_error("the simulator's clocks stood still for two minutes after the program");
      std::this_thread::sleep_for(std::chrono::milliseconds(250));
      after = clock();
      if (after.motion > moved.motion) moved = after;
    }
    if (!(after.first_motion > before.all)) throw std::runtime_error("the program ran without any motion");
    return {after.last_motion - after.first_motion, after.motion - before.motion};
  }

  // The tool length the simulator's tool table gives tool `id` (its Z column): G43 adds it to machine Z.
  double tool_length(int id) const {
    std::istringstream table(slurp(root_ + "/sim/" + table_));
    std::string line;
    while (std::getline(table, line)) {
      std::istringstream words(line);
      std::string w;
      if (!(words >> w) || w != "T" + std::to_string(id)) continue;
      while (words >> w)
        if (w[0] == 'Z') return std::stod(w.substr(1));
    }
    throw std::runtime_error("tool " + std::to_string(id) + " not in the simulator's tool table");
  }

 private:
  std::string table_, root_, programs_, failure_;
  int port_ = 0;
};

#define REQUIRE_MACHINE_SIMULATOR(sim, machine)                                                  \
  if (::access("/usr/bin/linuxcnc", X_OK) != 0) GTEST_SKIP() << "linuxcnc-uspace not installed"; \
  sim_test::Simulator sim(machine);                                                               \
  ASSERT_TRUE(sim.running()) << sim.failure()
#define REQUIRE_SIMULATOR(sim) REQUIRE_MACHINE_SIMULATOR(sim, "")

}  // namespace sim_test
