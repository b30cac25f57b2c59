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
#include "rosmill/input_file.hpp"

namespace rosmill::core::io {
namespace {

struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

[[noreturn]] void throw_open_error(const std::string& path, int err) {
  if (err == ENOENT) throw Error(path, "no such file");
  throw Error(path, std::string("cannot open: ") + std::strerror(err));
}

}  // namespace

FileBytes::FileBytes(const std::string& path, size_t max_bytes) {
  Fd file;
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then refuses it like any other non-regular file.
  file.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (file.fd < 0) throw_open_error(path, errno);
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) throw Error(path, std::string("cannot stat: ") + std::strerror(errno));
  mapping_size_ = check_input_stat(st, path, max_bytes);
  // MAP_POPULATE maps the page cache up front: one system call instead of a fault per page.
  void* p = ::mmap(nullptr, mapping_size_, PROT_READ, MAP_PRIVATE | MAP_POPULATE, file.fd, 0);
  if (p == MAP_FAILED) throw Error(path, std::string("cannot map: ") + std::strerror(errno));
  mapping_ = p;
  data_ = static_cast<const char*>(p);
  size_ = mapping_size_;
  if (is_gzip(data_, size_)) {
    std::vector<char> plain = gunzip(data_, size_, path, max_bytes);
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

namespace {

// Inflates every member of a gzip (or zlib) stream through a small window, handing each piece to `take`.
template <class Take>
void inflate_stream(const char* data, size_t size, const std::string& name, Take take) {
  z_stream zs{};
  // 15 + 32: the largest window, gzip or zlib header detected automatically.
  if (inflateInit2(&zs, 15 + 32) != Z_OK) throw Error(name, "cannot start gzip decompression");
  struct End {
    z_stream* zs;
    ~End() { inflateEnd(zs); }
  } end{&zs};
  std::vector<char> window(1 << 18);
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data));
  size_t in_left = size;
  for (;;) {
    if (zs.avail_in == 0 && in_left > 0) {
      const size_t chunk = std::min<size_t>(in_left, 1u << 30);
      zs.avail_in = static_cast<uInt>(chunk);
      in_left -= chunk;
    }
    zs.next_out = reinterpret_cast<Bytef*>(window.data());
    zs.avail_out = static_cast<uInt>(window.size());
    const int rc = inflate(&zs, Z_NO_FLUSH);
    take(window.data(), window.size() - zs.avail_out);
    if (rc == Z_STREAM_END) {
      // Concatenated gzip members are one file (gzip -c a b > c).
      if (zs.avail_in == 0 && in_left == 0) return;
      if (inflateReset(&zs) != Z_OK) return;
      continue;
    }
    if (rc == Z_BUF_ERROR && zs.avail_in == 0 && in_left == 0) throw Error(name, "truncated gzip stream");
    if (rc != Z_OK && rc != Z_BUF_ERROR)
      throw Error(name, std::string("corrupt gzip stream: ") + (zs.msg ? zs.msg : "error " + std::to_string(rc)));
  }
}

}  // namespace

std::vector<char> gunzip(const char* data, size_t size, const std::string& name, size_t max_bytes) {
  // Twice through the stream: first counting, so that a bomb is refused before anything of its size is
  // allocated (a growing buffer would hold up to 1.5 times the limit while it is copied), then into a buffer of
  // exactly the inflated size.
  size_t total = 0;
  inflate_stream(data, size, name, [&](const char*, size_t n) {
    total += n;
    if (total > max_bytes)
      throw Error(name, "gzip stream inflates to more than " + std::to_string(max_bytes >> 20) +
                            " MiB, the most rosmill reads");
  });
  std::vector<char> out(total);
  size_t used = 0;
  inflate_stream(data, size, name, [&](const char* piece, size_t n) {
    std::memcpy(out.data() + used, piece, n);
    used += n;
  });
  return out;
}

}  // namespace rosmill::core::io
