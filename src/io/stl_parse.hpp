// STL parsing from bytes in memory into a triangle soup (three corners per triangle, in the file's units).
// Internal to src/io: read_stl() and read_stl_buffer() wrap these with format detection and welding.
#pragma once
#include <cstddef>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core::io {

constexpr size_t kStlHeaderBytes = 80;
constexpr size_t kStlBinaryPrefix = 84;  // header + uint32 triangle count
constexpr size_t kStlRecordBytes = 50;   // normal, 3 corners (12 float32) + uint16 attribute

struct StlSoup {
  std::vector<Vec3> corners;  // 3 per triangle
  size_t solids = 0;
  size_t stored_normal_mismatches = 0;
};

// Triangle count declared by a binary header (bytes 80..83, little endian); size must be >= 84.
uint32_t binary_declared_count(const char* data);

// True when the first word of the buffer (after white space) is "solid", in any case.
bool starts_with_solid(const char* data, size_t size);

// Parses a binary body: `count` triangles starting at byte 84 (size already checked). Throws on NaN or infinity.
void parse_binary(const char* data, size_t count, const std::string& name, StlSoup& soup);

// Parses a binary body straight into welded vertices and faces (exact weld), without a corner soup: the body of
// a large file is touched once and no per-corner array is written. Throws like parse_binary().
void parse_binary_welded(const char* data, size_t count, const std::string& name, IndexedTriangles& out,
                         size_t& stored_normal_mismatches);

// Parses ASCII text; throws Error("name:line", what) on the first problem.
void parse_ascii(const char* data, size_t size, const std::string& name, StlSoup& soup);

// True when a stored normal disagrees with the corners' right-hand normal (zero stored normals and degenerate
// corners are not judged). Inline: binary loading calls it for every triangle.
inline bool stored_normal_disagrees(const Vec3& stored, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Judged at 10 degrees: exporters that write the CAD surface's normal at the facet differ from the flat
  // facet's normal by a few degrees on curved faces (featuretype.STL: up to 4.7); a flipped, stale or garbage
  // normal is far beyond that.
  constexpr double kCosTolerance = 0.98480775301220802;  // cos(10 degrees)
  const double stored_len2 = stored.squaredNorm();
  if (!(stored_len2 > 0.0)) return !std::isfinite(stored_len2);  // zero: not stored; NaN: wrong
  const Vec3 n = (b - a).cross(c - a);
  const double n_len2 = n.squaredNorm();
  if (!(n_len2 > 0.0)) return false;  // degenerate corners: nothing to compare with
  const double d = stored.dot(n);  // disagree when d < cos(10 deg) |stored| |n|; compared squared, no root
  return d < 0.0 || d * d < kCosTolerance * kCosTolerance * stored_len2 * n_len2;
}

}  // namespace rosmill::core::io
