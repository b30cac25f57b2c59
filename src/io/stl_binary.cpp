// Binary STL body: 50-byte records of little-endian float32 normal and corners, then a 16-bit attribute.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>

#include "rosmill/error.hpp"
#include "rosmill/geometry/vertex_welder.hpp"
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
  const double d = stored.dot(n);  // disagree when d < cos(10 deg) |stored| |n|; compared squared, no root
  return d < 0.0 || d * d < kCosTolerance * kCosTolerance * stored_len2 * n_len2;
}

namespace {

// Triangle t's corners into c[0..2]; counts a disagreeing stored normal. Throws on a non-finite coordinate.
void read_record(const char* data, size_t t, const std::string& name, Vec3* c, size_t& mismatches) {
  float f[12];
  std::memcpy(f, data + kStlBinaryPrefix + t * kStlRecordBytes, sizeof f);
  for (int i = 0; i < 3; ++i) {
    c[i] = Vec3(f[3 + 3 * i], f[4 + 3 * i], f[5 + 3 * i]);
    if (!c[i].allFinite())
      throw Error(name, "triangle " + std::to_string(t) + " (byte " +
                            std::to_string(kStlBinaryPrefix + t * kStlRecordBytes) +
                            ") has a coordinate that is not finite (NaN or infinity)");
  }
  if (stored_normal_disagrees(Vec3(f[0], f[1], f[2]), c[0], c[1], c[2])) ++mismatches;
}

}  // namespace

void parse_binary(const char* data, size_t count, const std::string& name, StlSoup& soup) {
  soup.corners.resize(3 * count);
  for (size_t t = 0; t < count; ++t) read_record(data, t, name, &soup.corners[3 * t], soup.stored_normal_mismatches);
}

namespace {

// Welds triangles [first, last) into `welder`, writing their faces (ids local to that welder).
void weld_range(const char* data, size_t first, size_t last, const std::string& name, VertexWelder& welder,
                std::array<uint32_t, 3>* faces, size_t& mismatches) {
  constexpr size_t kBatch = 16;  // triangles decoded, then welded together (the welder prefetches a batch)
  Vec3 corners[3 * kBatch];
  for (size_t t0 = first; t0 < last; t0 += kBatch) {
    const size_t m = std::min(kBatch, last - t0);
    for (size_t k = 0; k < m; ++k) read_record(data, t0 + k, name, corners + 3 * k, mismatches);
    welder.add_many(corners, 3 * m, faces[t0].data());
  }
}

}  // namespace

// Files of 32k triangles and more are welded in two halves side by side (below that the threads' start costs
// more than they save); the second half's vertices are then added to the first
// half's welder in their own order, which numbers every vertex exactly as one pass over the file would (first
// appearance), and the second half's faces are renumbered.
void parse_binary_welded(const char* data, size_t count, const std::string& name, IndexedTriangles& out,
                         size_t& stored_normal_mismatches) {
  out.faces.resize(count);
  const int parts = count >= 32768 ? 2 : 1;
  std::vector<VertexWelder> welders;
  // A closed mesh has about half as many vertices as triangles; the first welder ends up holding them all.
  for (int k = 0; k < parts; ++k) welders.emplace_back(k == 0 ? count / 2 + 16 : count / (2 * parts) + 16);
  std::vector<size_t> mismatches(parts, 0);
  std::vector<std::exception_ptr> failures(parts);
  auto bound = [&](int k) { return count * size_t(k) / size_t(parts); };
#pragma omp parallel for num_threads(parts) schedule(static, 1)
  for (int k = 0; k < parts; ++k) {
    try {
      weld_range(data, bound(k), bound(k + 1), name, welders[k], out.faces.data(), mismatches[k]);
    } catch (...) {
      failures[k] = std::current_exception();
    }
  }
  for (int k = 0; k < parts; ++k)  // the error a sequential read would have met first
    if (failures[k]) std::rethrow_exception(failures[k]);
  for (int k = 1; k < parts; ++k) {
    const std::vector<Vec3>& local = welders[k].vertices();
    std::vector<uint32_t> global(local.size());
    welders[0].add_many(local.data(), local.size(), global.data());
    const int64_t first = int64_t(bound(k)), last = int64_t(bound(k + 1));
#pragma omp parallel for schedule(static)
    for (int64_t t = first; t < last; ++t)
      for (uint32_t& v : out.faces[t]) v = global[v];
  }
  for (size_t m : mismatches) stored_normal_mismatches += m;
  out.vertices = welders[0].take_vertices();
}

}  // namespace rosmill::io
