// What both executables of the tool share: the app with its description, and one parse with every error printed
// the same way (rosmill::core::Error and any other exception: "rosmill: error: ...", exit 1).
#pragma once
#include <CLI/CLI.hpp>

namespace rosmill::core::cli {

constexpr const char* kAppDescription = "rosmill: from an STL part or a 3D scan to a milling program";

// Parses argv into `app` (whose callbacks do the work) and returns the exit status.
int run_cli(CLI::App& app, int argc, char** argv);

}  // namespace rosmill::core::cli
