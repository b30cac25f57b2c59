// rosmill: the command-line tool's front. `info` on a mesh, the command a user meets first, runs here, in a
// program that links neither PCL nor VTK (about 70 shared libraries fewer to load and relocate, most of the
// start-up); every other command, and `info` on a point cloud, replaces this process with rosmill-full from the
// same folder, with the same arguments.
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "../info_command.hpp"
#include "../run_cli.hpp"
#include "rosmill/heap_reuse.hpp"

namespace {

// The folder of this executable (not of argv[0], which a PATH search or a link may have named differently).
std::string own_folder() {
  char buf[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  const std::string path(buf, size_t(n));
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

[[noreturn]] void run_full(char** argv) {
  const std::string full = own_folder() + "/rosmill-full";
  ::execv(full.c_str(), argv);
  std::fprintf(stderr, "rosmill: error: cannot run %s: %s\n", full.c_str(), std::strerror(errno));
  std::exit(1);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "info") != 0) run_full(argv);
  rosmill::core::keep_freed_memory();  // as rosmill-full does (see heap_reuse.hpp)
  CLI::App app{rosmill::core::cli::kAppDescription};
  rosmill::core::cli::add_info_command(
      app, [argv](const std::string&, const std::string&) -> nlohmann::json { run_full(argv); });
  return rosmill::core::cli::run_cli(app, argc, argv);
}
