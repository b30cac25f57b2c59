// rosmill: the command-line tool's front, and rosmill-info. `info` on a mesh, the command a user meets first, runs
// in a program that links neither PCL nor VTK (about 70 shared libraries fewer to load and relocate); every other
// command, and `info` on a point cloud, replaces this process with rosmill-full from the same folder, with the
// same arguments. Built twice from this file:
// - rosmill (ROSMILL_SEQUENTIAL): no thread library and the C++ library linked in, so that a small file's whole
//   run costs less than loading those would; a mesh of kThreadedFrom bytes or more goes to rosmill-info.
// - rosmill-info: both cores, and huge pages for the heap a large load fills.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "../info_command.hpp"
#include "../run_cli.hpp"
#include "huge_pages.hpp"
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

// Replaces this process with `program` from the same folder, with the same arguments.
[[noreturn]] void run_instead(const char* program, char** argv) {
  const std::string path = own_folder() + "/" + program;
  ::execv(path.c_str(), argv);
  std::fprintf(stderr, "rosmill: error: cannot run %s: %s\n", path.c_str(), std::strerror(errno));
  std::exit(1);
}

[[noreturn]] void run_full(char** argv) { run_instead("rosmill-full", argv); }

// The largest regular file among the arguments (the mesh; options and their values name none), 0 if none.
size_t largest_file_argument(int argc, char** argv) {
  size_t largest = 0;
  for (int i = 2; i < argc; ++i) {
    struct stat st {};
    if (::stat(argv[i], &st) == 0 && S_ISREG(st.st_mode)) largest = std::max(largest, size_t(st.st_size));
  }
  return largest;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "info") != 0) run_full(argv);
#ifdef ROSMILL_SEQUENTIAL
  // From about 32,000 binary triangles on, the load's two halves on two cores save more than starting the
  // threaded program costs (a few milliseconds).
  constexpr size_t kThreadedFrom = size_t(2) << 20;
  if (largest_file_argument(argc, argv) >= kThreadedFrom) run_instead("rosmill-info", argv);
#else
  if (rosmill::core::keep_freed_memory())  // as rosmill-full does (see heap_reuse.hpp)
    // A binary STL's load writes about its own size in fresh arrays (welder tables, faces, vertices, half-edges),
    // an ASCII or gzip one less than its size times two; what is reserved but not written costs no memory.
    rosmill::core::cli::reserve_huge_page_heap(2 * largest_file_argument(argc, argv));
#endif
  CLI::App app{rosmill::core::cli::kAppDescription};
  rosmill::core::cli::add_info_command(
      app, [argv](const std::string&, const std::string&) -> nlohmann::json { run_full(argv); });
  return rosmill::core::cli::run_cli(app, argc, argv);
}
