// STL input and output, ASCII and binary. The format is told from content and size, never from the first five
// bytes ("solid" also starts many binary headers). Bad input throws rosmill::core::Error naming the file.
#pragma once
#include <string>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/units.hpp"

namespace rosmill::core {

struct StlReadOptions {
  Units units = Units::Millimetre;  // what the file's numbers are; the mesh comes back in millimetres
  WeldOptions weld;                 // tolerance in millimetres
};

struct StlInfo {
  bool ascii = false;
  size_t solids = 0;                    // ASCII: solid blocks read
  size_t stored_normal_mismatches = 0;  // stored normals more than 10 degrees off the corners' normal
};

// Reads path (also .stl.gz). Throws Error on any bad input.
Mesh read_stl(const std::string& path, const StlReadOptions& options = {}, StlInfo* info = nullptr);
// Reads an STL held in memory; `name` is used in error messages.
Mesh read_stl_buffer(const char* data, size_t size, const std::string& name, const StlReadOptions& options = {},
                     StlInfo* info = nullptr);

// The welded triangles alone (no normals, areas or edges): for viewers and markers, and the figure the issue's
// reference readers are compared on. Same checks and errors as read_stl().
IndexedTriangles read_stl_triangles(const std::string& path, const StlReadOptions& options = {},
                                    StlInfo* info = nullptr);
IndexedTriangles read_stl_triangles_buffer(const char* data, size_t size, const std::string& name,
                                           const StlReadOptions& options = {}, StlInfo* info = nullptr);

void write_stl(const std::string& path, const Mesh& mesh, bool ascii = false);

}  // namespace rosmill::core
