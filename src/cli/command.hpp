// Sub-commands of the `rosmill` tool register themselves: each src/cli/cmd_*.cpp holds one command and a
// static CommandRegistration, so commands are added without touching a shared list.
#pragma once
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace rosmill::core::cli {

// Adds its sub-command to the app; the sub-command's callback does the work and throws rosmill::core::Error on bad
// input (main prints it to stderr and exits 1).
using CommandSetup = std::function<void(CLI::App& app)>;

std::vector<CommandSetup>& command_setups();

struct CommandRegistration {
  explicit CommandRegistration(CommandSetup setup) { command_setups().push_back(std::move(setup)); }
};

}  // namespace rosmill::core::cli
