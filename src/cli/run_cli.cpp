#include "run_cli.hpp"

#include <cstdio>
#include <exception>

#include "rosmill/error.hpp"

namespace rosmill::core::cli {

int run_cli(CLI::App& app, int argc, char** argv) {
  app.require_subcommand(1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const Error& e) {
    std::fprintf(stderr, "rosmill: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rosmill: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace rosmill::core::cli
