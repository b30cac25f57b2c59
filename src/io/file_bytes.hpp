// The bytes of an input file, read once: mapped when it is a plain regular file, inflated into memory when it is
// gzip-compressed (recognised by its magic bytes, not its name). Internal to src/io.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace rosmill::core::io {

class FileBytes {
 public:
  // Throws Error naming `path` when it is missing, a directory, unreadable or a corrupt gzip stream.
  explicit FileBytes(const std::string& path);
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

// Checks that path names a readable, non-empty file; throws Error naming it otherwise (for readers, like PCL's,
// that open the file themselves and report problems poorly).
void check_input_file(const std::string& path);

// Inflates a gzip (or zlib) stream held in memory; `name` is used in error messages.
std::vector<char> gunzip(const char* data, size_t size, const std::string& name);

inline bool is_gzip(const char* data, size_t size) {
  return size >= 2 && static_cast<unsigned char>(data[0]) == 0x1f && static_cast<unsigned char>(data[1]) == 0x8b;
}

}  // namespace rosmill::core::io
