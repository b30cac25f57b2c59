#include "file_bytes.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "rosmill/error.hpp"

namespace rosmill::core::io {
namespace {

struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// Reads a file whose size stat() could not tell (a pipe, /proc): grows the buffer as bytes arrive.
std::vector<char> read_stream(int fd, const std::string& path) {
  std::vector<char> bytes;
  size_t used = 0;
  for (;;) {
    if (bytes.size() - used < 65536) bytes.resize(std::max<size_t>(2 * bytes.size(), 1 << 20));
    const ssize_t n = ::read(fd, bytes.data() + used, bytes.size() - used);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error(path, std::string("cannot read: ") + std::strerror(errno));
    }
    if (n == 0) break;
    used += static_cast<size_t>(n);
  }
  bytes.resize(used);
  return bytes;
}

[[noreturn]] void throw_open_error(const std::string& path, int err) {
  if (err == ENOENT) throw Error(path, "no such file");
  throw Error(path, std::string("cannot open: ") + std::strerror(err));
}

}  // namespace

void check_input_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw_open_error(path, errno);
  if (S_ISDIR(st.st_mode)) throw Error(path, "is a directory, not a file");
  if (::access(path.c_str(), R_OK) != 0) throw_open_error(path, errno);
  if (S_ISREG(st.st_mode) && st.st_size == 0) throw Error(path, "empty file");
}

FileBytes::FileBytes(const std::string& path) {
  Fd file;
  file.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (file.fd < 0) throw_open_error(path, errno);
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) throw Error(path, std::string("cannot stat: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw Error(path, "is a directory, not a file");

  if (S_ISREG(st.st_mode) && st.st_size > 0) {
    mapping_size_ = static_cast<size_t>(st.st_size);
    // MAP_POPULATE maps the page cache up front: one system call instead of a fault per page.
    void* p = ::mmap(nullptr, mapping_size_, PROT_READ, MAP_PRIVATE | MAP_POPULATE, file.fd, 0);
    if (p == MAP_FAILED) throw Error(path, std::string("cannot map: ") + std::strerror(errno));
    mapping_ = p;
    data_ = static_cast<const char*>(p);
    size_ = mapping_size_;
  } else if (!S_ISREG(st.st_mode)) {
    owned_ = read_stream(file.fd, path);
    data_ = owned_.data();
    size_ = owned_.size();
  }
  if (is_gzip(data_, size_)) {
    std::vector<char> plain = gunzip(data_, size_, path);
    if (mapping_) ::munmap(mapping_, mapping_size_);
    mapping_ = nullptr;
    owned_ = std::move(plain);
    data_ = owned_.data();
    size_ = owned_.size();
    gzipped_ = true;
  }
}

FileBytes::~FileBytes() {
  if (mapping_) ::munmap(mapping_, mapping_size_);
}

std::vector<char> gunzip(const char* data, size_t size, const std::string& name) {
  z_stream zs{};
  // 15 + 32: the largest window, gzip or zlib header detected automatically.
  if (inflateInit2(&zs, 15 + 32) != Z_OK) throw Error(name, "cannot start gzip decompression");
  // The gzip trailer's size field is a hint only (modulo 2^32, and untrusted): cap the first allocation.
  size_t guess = 4 * size;
  if (size >= 18) {
    uint32_t isize;
    std::memcpy(&isize, data + size - 4, 4);
    if (isize > size && isize <= 64 * size) guess = isize;
  }
  std::vector<char> out(std::max<size_t>(guess, 4096));
  size_t used = 0;
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data));
  size_t in_left = size;
  int rc = Z_OK;
  for (;;) {
    if (zs.avail_in == 0 && in_left > 0) {
      const size_t chunk = std::min<size_t>(in_left, 1u << 30);
      zs.avail_in = static_cast<uInt>(chunk);
      in_left -= chunk;
    }
    if (used == out.size()) out.resize(out.size() * 2);
    const size_t room = std::min<size_t>(out.size() - used, 1u << 30);
    zs.next_out = reinterpret_cast<Bytef*>(out.data() + used);
    zs.avail_out = static_cast<uInt>(room);
    rc = inflate(&zs, Z_NO_FLUSH);
    used += room - zs.avail_out;
    if (rc == Z_STREAM_END) {
      // Concatenated gzip members are one file (gzip -c a b > c).
      if (zs.avail_in == 0 && in_left == 0) break;
      if (inflateReset(&zs) != Z_OK) break;
      continue;
    }
    if (rc == Z_BUF_ERROR && zs.avail_in == 0 && in_left == 0) {
      inflateEnd(&zs);
      throw Error(name, "truncated gzip stream");
    }
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      const std::string msg = zs.msg ? zs.msg : "error " + std::to_string(rc);
      inflateEnd(&zs);
      throw Error(name, "corrupt gzip stream: " + msg);
    }
  }
  inflateEnd(&zs);
  out.resize(used);
  return out;
}

}  // namespace rosmill::core::io
