#include "rosmill/input_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "rosmill/error.hpp"

namespace rosmill::core {
namespace {

[[noreturn]] void throw_open_error(const std::string& path, int err) {
  if (err == ENOENT) throw Error(path, "no such file");
  throw Error(path, std::string("cannot open: ") + std::strerror(err));
}

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

size_t check_input_stat(const struct stat& st, const std::string& path, size_t max_bytes) {
  if (!S_ISREG(st.st_mode)) throw Error(path, std::string("is ") + kind_of(st.st_mode) + ", not a regular file");
  if (st.st_size == 0) throw Error(path, "empty file");
  const size_t size = static_cast<size_t>(st.st_size);
  if (size > max_bytes) {
    char text[160];
    std::snprintf(text, sizeof text, "file of %zu bytes is larger than the %zu bytes (%.0f MiB) rosmill reads", size,
                  max_bytes, double(max_bytes) / (1 << 20));
    throw Error(path, text);
  }
  return size;
}

size_t check_input_file(const std::string& path, size_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw_open_error(path, errno);
  const size_t size = check_input_stat(st, path, max_bytes);
  if (::access(path.c_str(), R_OK) != 0) throw_open_error(path, errno);
  return size;
}

std::string read_input_file(const std::string& path, size_t max_bytes) {
  // O_NONBLOCK: a FIFO swapped in after a stat() must not block the open; it is refused by fstat below.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw_open_error(path, errno);
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw Error(path, std::string("cannot stat: ") + std::strerror(errno));
  std::string text(check_input_stat(st, path, max_bytes), '\0');
  size_t used = 0;
  while (used < text.size()) {
    const ssize_t n = ::read(fd, &text[used], text.size() - used);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error(path, std::string("cannot read: ") + std::strerror(errno));
    if (n == 0) break;  // the file shrank while read
    used += static_cast<size_t>(n);
  }
  text.resize(used);
  return text;
}

}  // namespace rosmill::core
