// What the job tests run with: the package's tool table, a machine file of the package checking every program (and
// giving its accelerations to the time estimate), and a fresh scratch folder per test.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/job/job_options.hpp"

namespace job_test {

inline const rosmill::core::ToolTable& package_tools() {
  static const rosmill::core::ToolTable t =
      rosmill::core::read_tool_table(std::string(ROSMILL_SOURCE_DIR) + "/config/tools.yaml");
  return t;
}

// `machine`: a file name in the package's config/ (machine.yaml: LinuxCNC's 3-axis simulator).
// Built as `rosmill job` and the plan_job action build theirs.
inline rosmill::core::job::JobOptions options(const std::string& out = "", const std::string& machine = "machine.yaml") {
  rosmill::core::job::JobRequest request;
  request.tools = &package_tools();
  request.out_dir = out;
  request.machine = rosmill::core::gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/" + machine);
  return rosmill::core::job::job_options(request);
}

// An empty folder named for the test.
inline std::string scratch(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "rosmill_" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace job_test
