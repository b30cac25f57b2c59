// Binary STL body: 50-byte records of little-endian float32 normal and corners, then a 16-bit attribute.
#include <Eigen/Geometry>
#include <cmath>
#include <cstring>

#include "rosmill/error.hpp"
#include "stl_parse.hpp"

namespace rosmill::io {

uint32_t binary_declared_count(const char* data) {
  uint32_t count;
  std::memcpy(&count, data + kStlHeaderBytes, sizeof count);
  return count;
}

bool stored_normal_disagrees(const Vec3& stored, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Judged at 10 degrees: exporters that write the CAD surface's normal at the facet differ from the flat
  // facet's normal by a few degrees on curved faces (featuretype.STL: up to 4.7); a flipped, stale or garbage
  // normal is far beyond that.
  constexpr double kCosTolerance = 0.98480775301220802;  // cos(10 degrees)
  const double stored_len2 = stored.squaredNorm();
  if (!(stored_len2 > 0.0)) return !std::isfinite(stored_len2);  // zero: not stored; NaN: wrong
  const Vec3 n = (b - a).cross(c - a);
  const double n_len2 = n.squaredNorm();
  if (!(n_len2 > 0.0)) return false;  // degenerate corners: nothing to compare with
  return stored.dot(n) < kCosTolerance * std::sqrt(stored_len2 * n_len2);
}

void parse_binary(const char* data, size_t count, const std::string& name, StlSoup& soup) {
  soup.corners.resize(3 * count);
  const char* record = data + kStlBinaryPrefix;
  for (size_t t = 0; t < count; ++t, record += kStlRecordBytes) {
    float f[12];
    std::memcpy(f, record, sizeof f);
    for (int i = 0; i < 3; ++i) {
      const Vec3 v(f[3 + 3 * i], f[4 + 3 * i], f[5 + 3 * i]);
      if (!v.allFinite())
        throw Error(name, "triangle " + std::to_string(t) + " (byte " +
                              std::to_string(kStlBinaryPrefix + t * kStlRecordBytes) +
                              ") has a coordinate that is not finite (NaN or infinity)");
      soup.corners[3 * t + i] = v;
    }
    if (stored_normal_disagrees(Vec3(f[0], f[1], f[2]), soup.corners[3 * t], soup.corners[3 * t + 1],
                                soup.corners[3 * t + 2]))
      ++soup.stored_normal_mismatches;
  }
}

}  // namespace rosmill::io
