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

namespace rosmill::core {
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
  if (needed > size) {
    const std::string sizes = "the header's triangle count " + std::to_string(count) + " needs " +
                              size_text(needed) + ", the file has " + size_text(size);
    // Far beyond the file: the count field is not a count, the file is not STL at all.
    if (needed / 16 > size) throw Error(name, "not an STL file, or a binary STL with a corrupt header: " + sizes);
    throw Error(name, "truncated binary STL: " + sizes);
  }
  return static_cast<size_t>(count);
}

// What the parser produced: a corner soup (ASCII, or binary to be welded with a tolerance) or, for binary files
// welded exactly, the indexed mesh itself.
struct Parsed {
  bool ascii = false;
  io::StlSoup soup;
  IndexedTriangles indexed;
  size_t indexed_mismatches = 0;
  bool is_indexed = false;
};

void parse_binary_body(const char* data, size_t size, const std::string& name, bool weld_directly, Parsed& out) {
  out.ascii = false;
  const size_t count = checked_binary_count(data, size, name);
  if (weld_directly) {
    io::parse_binary_welded(data, count, name, out.indexed, out.indexed_mismatches);
    out.is_indexed = true;
  } else {
    io::parse_binary(data, count, name, out.soup);
  }
}

void parse(const char* data, size_t size, const std::string& name, bool weld_directly, Parsed& out) {
  if (size == 0) throw Error(name, "empty file");
  const bool solid = io::starts_with_solid(data, size);
  const bool has_prefix = size >= kStlBinaryPrefix;
  const uint64_t declared = has_prefix ? io::binary_declared_count(data) : 0;
  const uint64_t needed = kStlBinaryPrefix + kStlRecordBytes * declared;

  if (has_prefix && needed == size) {  // size agrees with the count: binary, whatever the header says
    parse_binary_body(data, size, name, weld_directly, out);
    return;
  }
  if (solid) {
    try {
      out.ascii = true;
      io::parse_ascii(data, size, name, out.soup);
      return;
    } catch (const Error&) {
      // A binary body followed by extra bytes under a header that starts with "solid", or a binary file that is
      // broken (it is judged as binary, since its bytes are not text).
      const bool binary_fits = has_prefix && declared > 0 && needed < size;
      if (!binary_fits && !(has_prefix && !looks_like_text(data, std::min<size_t>(size, 4096)))) throw;
      out.soup = io::StlSoup{};
    }
    parse_binary_body(data, size, name, weld_directly, out);
    return;
  }
  if (!has_prefix) {
    if (looks_like_text(data, size))
      throw Error(name, "not an STL file: text that does not begin with 'solid'");
    throw Error(name, "not an STL file: " + size_text(size) + ", shorter than a binary STL header (84 bytes)");
  }
  if (looks_like_text(data, std::min<size_t>(size, 4096)))
    throw Error(name, "not an STL file: text that does not begin with 'solid'");
  parse_binary_body(data, size, name, weld_directly, out);
}

}  // namespace

IndexedTriangles read_stl_triangles_buffer(const char* data, size_t size, const std::string& name,
                                           const StlReadOptions& options, StlInfo* info) {
  if (io::is_gzip(data, size)) {
    const std::vector<char> plain = io::gunzip(data, size, name);
    return read_stl_triangles_buffer(plain.data(), plain.size(), name, options, info);
  }
  Parsed parsed;
  parse(data, size, name, options.weld.tolerance <= 0.0, parsed);
  const double scale = mm_per_unit(options.units);
  // Weld in the file's units (exact welding compares the file's own numbers); the tolerance is in millimetres.
  WeldOptions weld = options.weld;
  weld.tolerance /= scale;
  IndexedTriangles triangles = parsed.is_indexed ? std::move(parsed.indexed) : weld_corners(parsed.soup.corners, weld);
  if (scale != 1.0)
    for (Vec3& v : triangles.vertices) v *= scale;
  if (info) {
    info->ascii = parsed.ascii;
    info->solids = parsed.ascii ? parsed.soup.solids : 0;
    info->stored_normal_mismatches = parsed.is_indexed ? parsed.indexed_mismatches : parsed.soup.stored_normal_mismatches;
  }
  return triangles;
}

Mesh read_stl_buffer(const char* data, size_t size, const std::string& name, const StlReadOptions& options,
                     StlInfo* info) {
  return mesh_from_indexed(read_stl_triangles_buffer(data, size, name, options, info));
}

IndexedTriangles read_stl_triangles(const std::string& path, const StlReadOptions& options, StlInfo* info) {
  const io::FileBytes bytes(path);
  return read_stl_triangles_buffer(bytes.data(), bytes.size(), path, options, info);
}

Mesh read_stl(const std::string& path, const StlReadOptions& options, StlInfo* info) {
  return mesh_from_indexed(read_stl_triangles(path, options, info));
}

}  // namespace rosmill::core
