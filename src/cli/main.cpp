// rosmill: the core pipeline from the command line, no ROS master needed.
#include <cstdio>
#include <exception>

#include "command.hpp"
#include "rosmill/error.hpp"
#include "rosmill/heap_reuse.hpp"

namespace rosmill::core::cli {
std::vector<CommandSetup>& command_setups() {
  static std::vector<CommandSetup> setups;
  return setups;
}
}  // namespace rosmill::core::cli

int main(int argc, char** argv) {
  rosmill::core::keep_freed_memory();  // repeated jobs reuse their memory (see heap_reuse.hpp)
  CLI::App app{"rosmill: from an STL part or a 3D scan to a milling program"};
  app.require_subcommand(1);
  for (auto& setup : rosmill::core::cli::command_setups()) setup(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const rosmill::core::Error& e) {
    std::fprintf(stderr, "rosmill: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rosmill: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
