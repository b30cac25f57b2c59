// What rosmill accepts as an input file, as one policy for every reader (meshes, clouds, G-code, toolpaths, tool,
// machine and preset tables): a regular file, readable, not empty and not larger than kMaxInputBytes, and a
// compressed file not inflating beyond the same size. A device (/dev/zero), a FIFO or a socket would otherwise be
// read until memory runs out, and a gzip bomb would do the same from a few kilobytes.
#pragma once
#include <sys/stat.h>

#include <cstddef>
#include <string>

namespace rosmill::core {

// 1 GiB: an ASCII STL of two million triangles is about half of it; beyond it a file is a mistake or an attack.
constexpr size_t kMaxInputBytes = size_t(1) << 30;

// Throws Error naming `path` when st (from stat or fstat of it) is not a regular file or is empty or larger than
// max_bytes. Returns its size.
size_t check_input_stat(const struct stat& st, const std::string& path, size_t max_bytes = kMaxInputBytes);

// stat()s path (without opening it: opening a FIFO blocks) and checks it as above; also that it is readable.
size_t check_input_file(const std::string& path, size_t max_bytes = kMaxInputBytes);

// The whole file as text (YAML, JSON, G-code), under the policy. Throws Error naming path.
std::string read_input_file(const std::string& path, size_t max_bytes = kMaxInputBytes);

}  // namespace rosmill::core
