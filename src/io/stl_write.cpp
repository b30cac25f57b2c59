// write_stl: binary (float32, as the format stores) or ASCII (shortest text that reads back to the same double).
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <memory>

#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "stl_parse.hpp"

namespace rosmill::core {
namespace {

std::string binary_stl(const Mesh& mesh) {
  const size_t n = mesh.faces.size();
  if (n > 0xffffffffu) throw Error("write_stl", "too many triangles for a binary STL");
  std::string out(io::kStlBinaryPrefix + io::kStlRecordBytes * n, '\0');
  // The header must not begin with "solid": readers that look only at the first bytes would take it for ASCII.
  const char header[] = "binary STL written by rosmill";
  std::memset(out.data(), ' ', io::kStlHeaderBytes);
  std::memcpy(out.data(), header, sizeof header - 1);
  const uint32_t count = static_cast<uint32_t>(n);
  std::memcpy(out.data() + io::kStlHeaderBytes, &count, 4);
  char* record = out.data() + io::kStlBinaryPrefix;
  for (size_t f = 0; f < n; ++f, record += io::kStlRecordBytes) {
    float v[12];
    for (int k = 0; k < 3; ++k) v[k] = static_cast<float>(mesh.normals[f][k]);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) v[3 + 3 * i + k] = static_cast<float>(mesh.corner(f, i)[k]);
    std::memcpy(record, v, sizeof v);  // the 2 attribute bytes stay zero
  }
  return out;
}

void append_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void append_triple(std::string& out, const char* keyword, const Vec3& v) {
  out += keyword;
  for (int k = 0; k < 3; ++k) {
    out += ' ';
    append_number(out, v[k]);
  }
  out += '\n';
}

std::string ascii_stl(const Mesh& mesh) {
  std::string out;
  out.reserve(64 + 200 * mesh.faces.size());
  out += "solid rosmill\n";
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    append_triple(out, "  facet normal", mesh.normals[f]);
    out += "    outer loop\n";
    for (int i = 0; i < 3; ++i) append_triple(out, "      vertex", mesh.corner(f, i));
    out += "    endloop\n  endfacet\n";
  }
  out += "endsolid rosmill\n";
  return out;
}

}  // namespace

void write_stl(const std::string& path, const Mesh& mesh, bool ascii) {
  const std::string bytes = ascii ? ascii_stl(mesh) : binary_stl(mesh);
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!file) throw Error(path, std::string("cannot write: ") + std::strerror(errno));
  if (std::fwrite(bytes.data(), 1, bytes.size(), file.get()) != bytes.size())
    throw Error(path, std::string("write failed: ") + std::strerror(errno));
  if (std::fclose(file.release()) != 0) throw Error(path, std::string("write failed: ") + std::strerror(errno));
}

}  // namespace rosmill::core
