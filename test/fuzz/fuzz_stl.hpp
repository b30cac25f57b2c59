// The STL properties both STL targets check (ASCII and binary differ by their seeds and dictionary: the format
// is told from content and size, as for a user's file). read_stl_buffer() is the whole reader: detection,
// parsing, welding, then the mesh's normals and edges.
#pragma once
#include "fuzz_support.hpp"
#include "rosmill/io/stl.hpp"

namespace rosmill::fuzz {

inline void read_stl_checked(const uint8_t* data, size_t size) {
  read_or_refuse([&] {
    core::StlInfo info;
    const core::Mesh mesh = core::read_stl_buffer(reinterpret_cast<const char*>(data), size, "fuzz.stl", {}, &info);
    require(!mesh.faces.empty(), "a mesh without triangles was accepted");
    for (const core::Vec3& v : mesh.vertices) require(v.allFinite(), "a vertex that is not finite");
    for (const auto& f : mesh.faces)
      for (int k = 0; k < 3; ++k) require(f[k] < mesh.vertices.size(), "a face index beyond the vertices");
  });
}

}  // namespace rosmill::fuzz
