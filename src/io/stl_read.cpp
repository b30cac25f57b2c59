// read_stl: tells ASCII from binary by content and size, parses, welds, scales to millimetres.
//
// The first five bytes decide nothing: many binary files (ktoolcav.stl among them) start their free-form 80-byte
// header with "solid". A binary file is recognised by its size agreeing with its declared triangle count; ASCII
// is tried when the text starts with "solid", and a binary body with trailing bytes is accepted when ASCII
// parsing fails and the declared triangles fit in the file.
#include <algorithm>
#include <cctype>

#include "file_bytes.hpp"
#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "stl_parse.hpp"

namespace rosmill {
namespace {

using io::kStlBinaryPrefix;
using io::kStlRecordBytes;

// True when the bytes look like text (printable ASCII, white space or UTF-8): a text file that does not start
// with "solid" is reported as "not an STL file" rather than as a binary file with an absurd triangle count.
bool looks_like_text(const char* data, size_t size) {
  for (size_t i = 0; i < size; ++i) {
    const unsigned char c = static_cast<unsigned char>(data[i]);
    if (c < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v') return false;
    if (c == 0x7f) return false;
  }
  return true;
}

std::string size_text(uint64_t bytes) { return std::to_string(bytes) + " bytes"; }

// Binary layout check; returns the declared count when the body fits, throws otherwise.
size_t checked_binary_count(const char* data, size_t size, const std::string& name) {
  const uint64_t count = io::binary_declared_count(data);
  const uint64_t needed = kStlBinaryPrefix + kStlRecordBytes * count;
  if (count == 0) throw Error(name, "binary STL declares zero triangles (no geometry)");
  if (needed > size)
    throw Error(name, "truncated binary STL: the header declares " + std::to_string(count) + " triangles (" +
                          size_text(needed) + ") but the file has " + size_text(size));
  return static_cast<size_t>(count);
}

void parse_soup(const char* data, size_t size, const std::string& name, io::StlSoup& soup, bool& ascii) {
  if (size == 0) throw Error(name, "empty file");
  const bool solid = io::starts_with_solid(data, size);
  const bool has_prefix = size >= kStlBinaryPrefix;
  const uint64_t declared = has_prefix ? io::binary_declared_count(data) : 0;
  const uint64_t needed = kStlBinaryPrefix + kStlRecordBytes * declared;

  if (has_prefix && needed == size) {  // size agrees with the count: binary, whatever the header says
    ascii = false;
    io::parse_binary(data, checked_binary_count(data, size, name), name, soup);
    return;
  }
  if (solid) {
    try {
      ascii = true;
      io::parse_ascii(data, size, name, soup);
      return;
    } catch (const Error&) {
      // A binary body followed by extra bytes under a header that starts with "solid", or a binary file that is
      // broken (it is judged as binary, since its bytes are not text).
      const bool binary_fits = has_prefix && declared > 0 && needed < size;
      if (!binary_fits && !(has_prefix && !looks_like_text(data, std::min<size_t>(size, 4096)))) throw;
      soup = io::StlSoup{};
    }
    ascii = false;
    io::parse_binary(data, checked_binary_count(data, size, name), name, soup);
    return;
  }
  if (!has_prefix) {
    if (looks_like_text(data, size))
      throw Error(name, "not an STL file: text that does not begin with 'solid'");
    throw Error(name, "not an STL file: " + size_text(size) + ", shorter than a binary STL header (84 bytes)");
  }
  if (looks_like_text(data, std::min<size_t>(size, 4096)))
    throw Error(name, "not an STL file: text that does not begin with 'solid'");
  ascii = false;
  io::parse_binary(data, checked_binary_count(data, size, name), name, soup);
}

}  // namespace

Mesh read_stl_buffer(const char* data, size_t size, const std::string& name, const StlReadOptions& options,
                     StlInfo* info) {
  if (io::is_gzip(data, size)) {
    const std::vector<char> plain = io::gunzip(data, size, name);
    return read_stl_buffer(plain.data(), plain.size(), name, options, info);
  }
  io::StlSoup soup;
  bool ascii = false;
  parse_soup(data, size, name, soup, ascii);
  const double scale = mm_per_unit(options.units);
  // Weld in the file's units (exact welding compares the file's own numbers); the tolerance is in millimetres.
  WeldOptions weld = options.weld;
  weld.tolerance /= scale;
  Mesh mesh = build_mesh(soup.corners, weld);
  scale_mesh(mesh, scale);
  if (info) {
    info->ascii = ascii;
    info->solids = ascii ? soup.solids : 0;
    info->stored_normal_mismatches = soup.stored_normal_mismatches;
  }
  return mesh;
}

Mesh read_stl(const std::string& path, const StlReadOptions& options, StlInfo* info) {
  const io::FileBytes bytes(path);
  return read_stl_buffer(bytes.data(), bytes.size(), path, options, info);
}

}  // namespace rosmill
