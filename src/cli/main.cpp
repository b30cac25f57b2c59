// rosmill-full: every command of the rosmill tool (the `rosmill` front runs `info` on a mesh itself and hands
// everything else to this program), the core pipeline from the command line, no ROS master needed.
#include "command.hpp"
#include "rosmill/heap_reuse.hpp"
#include "run_cli.hpp"

namespace rosmill::core::cli {
std::vector<CommandSetup>& command_setups() {
  static std::vector<CommandSetup> setups;
  return setups;
}
}  // namespace rosmill::core::cli

int main(int argc, char** argv) {
  rosmill::core::keep_freed_memory();  // repeated jobs reuse their memory (see heap_reuse.hpp)
  CLI::App app{rosmill::core::cli::kAppDescription};
  for (auto& setup : rosmill::core::cli::command_setups()) setup(app);
  return rosmill::core::cli::run_cli(app, argc, argv);
}
