// The bytes of an input file, read once: mapped when it is a plain regular file, inflated into memory when it is
// gzip-compressed (recognised by its magic bytes, not its name). Internal to src/io.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "rosmill/input_file.hpp"

namespace rosmill::core::io {

class FileBytes {
 public:
  // Throws Error naming `path` when it breaks the input policy (rosmill/input_file.hpp: a regular file of at most
  // max_bytes, inflating to at most as many), is unreadable or is a corrupt gzip stream.
  explicit FileBytes(const std::string& path, size_t max_bytes = kMaxInputBytes);
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;

  const char* data() const { return data_; }
  size_t size() const { return size_; }
  bool gzipped() const { return gzipped_; }

 private:
  const char* data_ = nullptr;
  size_t size_ = 0;
  void* mapping_ = nullptr;  // munmap()ed on destruction when set
  size_t mapping_size_ = 0;
  std::vector<char> owned_;  // read or inflated bytes
  bool gzipped_ = false;
};

// Inflates a gzip (or zlib) stream held in memory; `name` is used in error messages. Throws Error when the stream
// inflates to more than max_bytes, before allocating it.
std::vector<char> gunzip(const char* data, size_t size, const std::string& name, size_t max_bytes = kMaxInputBytes);

inline bool is_gzip(const char* data, size_t size) {
  return size >= 2 && static_cast<unsigned char>(data[0]) == 0x1f && static_cast<unsigned char>(data[1]) == 0x8b;
}

}  // namespace rosmill::core::io
