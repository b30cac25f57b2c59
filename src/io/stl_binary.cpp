// Binary STL body: 50-byte records of little-endian float32 normal and corners, then a 16-bit attribute.
#include <Eigen/Geometry>
#include <algorithm>
#include <cstring>
#include <exception>

#include "rosmill/error.hpp"
#include "rosmill/heap_reuse.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/geometry/vertex_welder.hpp"
#include "stl_parse.hpp"

namespace rosmill::core::io {

uint32_t binary_declared_count(const char* data) {
  uint32_t count;
  std::memcpy(&count, data + kStlHeaderBytes, sizeof count);
  return count;
}

namespace {

using CornerKey = FloatWelder::Key;
static_assert(sizeof(CornerKey) == 3 * sizeof(uint32_t), "a corner key is its three float32 words");
constexpr size_t kWords = 12;  // float32 words of a record: the stored normal (3), then the corners (9)
constexpr size_t kBatch = 32;  // triangles decoded, then welded together (the welder prefetches them at once)

// The exponent bits of the corner words of a batch (a stored normal that is not finite is judged, not refused).
struct CornerExponents {
  uint32_t mask[kBatch * kWords];
  constexpr CornerExponents() : mask() {
    for (size_t i = 0; i < kBatch * kWords; ++i) mask[i] = i % kWords >= 3 ? 0x7f800000u : 0u;
  }
};
constexpr CornerExponents kCornerExponents;

float as_float(uint32_t word) {
  float f;
  std::memcpy(&f, &word, sizeof f);
  return f;
}

bool finite_word(uint32_t word) { return (word & 0x7f800000u) != 0x7f800000u; }

[[noreturn]] void throw_not_finite(const uint32_t* words, size_t t0, size_t m, const std::string& name) {
  size_t k = 0;
  while (k + 1 < m && std::all_of(words + kWords * k + 3, words + kWords * (k + 1), finite_word)) ++k;
  const size_t t = t0 + k;
  throw Error(name, "triangle " + std::to_string(t) + " (byte " + std::to_string(kStlBinaryPrefix + t * kStlRecordBytes) +
                        ") has a coordinate that is not finite (NaN or infinity)");
}

// Triangles [t0, t0 + m) as 3 m corner keys (their float32 bit patterns); counts disagreeing stored normals.
// Throws at the first corner that is not finite.
void decode_batch(const char* data, size_t t0, size_t m, const std::string& name, CornerKey* keys,
                  size_t& mismatches) {
  uint32_t words[kBatch * kWords];
  for (size_t k = 0; k < m; ++k)
    std::memcpy(words + kWords * k, data + kStlBinaryPrefix + (t0 + k) * kStlRecordBytes, kWords * sizeof(uint32_t));
  // An all-ones exponent (NaN, infinity) carries into bit 31 when one exponent unit is added; -0 becomes +0
  // (the keys' rule). No branch per word, so the loop vectorizes.
  uint32_t carry = 0;
  for (size_t i = 0; i < kWords * m; ++i) {
    const uint32_t word = words[i];
    carry |= (word & kCornerExponents.mask[i]) + 0x00800000u;
    words[i] = weld_word(as_float(word));
  }
  if (carry & 0x80000000u) throw_not_finite(words, t0, m, name);
  for (size_t k = 0; k < m; ++k) {
    const uint32_t* w = words + kWords * k;
    Vec3 f[4];  // the stored normal and the corners (-0 folded, which changes no comparison of the check)
    for (int i = 0; i < 4; ++i) f[i] = Vec3(as_float(w[3 * i]), as_float(w[3 * i + 1]), as_float(w[3 * i + 2]));
    if (stored_normal_disagrees(f[0], f[1], f[2], f[3])) ++mismatches;
    std::memcpy(keys[3 * k].data(), w + 3, 3 * sizeof(CornerKey));
  }
}

// Welds triangles [first, last) into `welder`, writing their faces (ids local to that welder).
void weld_range(const char* data, size_t first, size_t last, const std::string& name, FloatWelder& welder,
                Mesh::Face* faces, size_t& mismatches) {
  CornerKey keys[3 * kBatch];
  for (size_t t0 = first; t0 < last; t0 += kBatch) {
    const size_t m = std::min(kBatch, last - t0);
    decode_batch(data, t0, m, name, keys, mismatches);
    welder.add_many(keys, 3 * m, faces[t0].data());
  }
}

// Loops over vertices and faces on both cores from `grain` items on, in pieces taken on demand, so that the
// calling thread goes on while a sleeping worker wakes (a shorter range stays on the calling thread).
template <typename Body>
void for_each_item(int64_t first, int64_t last, int64_t grain, const Body& body) {
  for_each_piece(first, last, grain, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) body(i);
  });
}

constexpr int64_t kParallelVertices = 100000;

// The welder's vertex positions into vertices[0, size).
void write_positions(const FloatWelder& welder, Vec3* vertices) {
  for_each_item(0, int64_t(welder.size()), kParallelVertices,
             [&](int64_t v) { vertices[v] = key_position(welder.keys()[v]); });
}

// The second half's vertex ids in the whole file's numbering: a vertex the first half also has keeps the first
// half's id, the others follow the first half's vertices in their own order. That is exactly the numbering of
// one pass over the whole file (first appearance), and no key is inserted again.
void merge_ids(const FloatWelder& first, const FloatWelder& second, std::vector<uint32_t>& ids,
               size_t& vertex_count) {
  if (first.size() + second.size() >= FloatWelder::kAbsent)
    throw Error("mesh", "more than 4,294,967,294 distinct vertices");
  const int64_t n = int64_t(second.size());
  constexpr int64_t kChunk = 4096;  // keys looked up together (the welder prefetches their slots at once)
  ids.resize(static_cast<size_t>(n));
  for_each_item(0, (n + kChunk - 1) / kChunk, 1, [&](int64_t k) {
    const int64_t c = k * kChunk;
    first.find_many(second.keys() + c, size_t(std::min(kChunk, n - c)), ids.data() + c);
  });
  uint32_t next = uint32_t(first.size());
  for (uint32_t& id : ids)
    if (id == FloatWelder::kAbsent) id = next++;
  vertex_count = next;
}

}  // namespace

void parse_binary(const char* data, size_t count, const std::string& name, StlSoup& soup) {
  soup.corners.resize(3 * count);
  CornerKey keys[3 * kBatch];
  for (size_t t0 = 0; t0 < count; t0 += kBatch) {
    const size_t m = std::min(kBatch, count - t0);
    decode_batch(data, t0, m, name, keys, soup.stored_normal_mismatches);
    for (size_t i = 0; i < 3 * m; ++i) soup.corners[3 * t0 + i] = key_position(keys[i]);
  }
}

// Files of 32k triangles and more are welded in two halves side by side (below that the threads' start costs
// more than they save), each half in its own welder, built by its own thread; then merge_ids() numbers the
// second half's vertices in the whole file's order and its faces are renumbered.
void parse_binary_welded(const char* data, size_t count, const std::string& name, IndexedTriangles& out,
                         size_t& stored_normal_mismatches) {
  out.faces.reserve(count);
  fault_in_on_both_cores(out.faces.data(), count * sizeof(Mesh::Face));  // before resize() zero-fills it
  out.faces.resize(count);
  if (count < 32768) {
    FloatWelder welder(count / 2 + 16);  // a closed mesh has about half as many vertices as triangles
    weld_range(data, 0, count, name, welder, out.faces.data(), stored_normal_mismatches);
    out.vertices.resize(welder.size());
    write_positions(welder, out.vertices.data());
    return;
  }
  const size_t half = count / 2;
  // The heap's order, so that the vertices below reuse the memory the tables had (most of it: fresh pages are
  // dear, heap_reuse.hpp): both welders' keys and the merge's ids first, then the tables, side by side at the top,
  // made by the first keys added and released before the vertices are written.
  const size_t expected = count / 4 + count / 16;  // a quarter of the triangles' count, and the seam
  FloatWelder welders[2] = {FloatWelder(expected), FloatWelder(expected)};
  std::vector<uint32_t> ids;
  ids.reserve(expected);
  size_t mismatches[2] = {0, 0};
  std::exception_ptr failures[2];
  auto weld_half = [&](int k) {
    try {
      weld_range(data, k == 0 ? 0 : half, k == 0 ? half : count, name, welders[k], out.faces.data(), mismatches[k]);
    } catch (...) {
      failures[k] = std::current_exception();
    }
  };
  // Exactly two tasks: the merge below numbers the vertices of two welders, one per half.
  run_both([&] { weld_half(0); }, [&] { weld_half(1); });
  for (const std::exception_ptr& failure : failures)  // the error a sequential read would have met first
    if (failure) std::rethrow_exception(failure);
  stored_normal_mismatches += mismatches[0] + mismatches[1];

  FloatWelder& first = welders[0];
  FloatWelder& second = welders[1];
  size_t vertex_count = 0;
  merge_ids(first, second, ids, vertex_count);
  first.release_table();
  second.release_table();
  out.vertices.reserve(vertex_count);
  fault_in_on_both_cores(out.vertices.data(), vertex_count * sizeof(Vec3));  // before resize() zero-fills it
  out.vertices.resize(vertex_count);
  write_positions(first, out.vertices.data());
  for_each_item(0, int64_t(ids.size()), kParallelVertices, [&](int64_t v) {
    if (ids[v] >= first.size()) out.vertices[ids[v]] = key_position(second.keys()[v]);
  });
  for_each_item(int64_t(half), int64_t(count), 1, [&](int64_t t) {
    for (uint32_t& v : out.faces[t]) v = ids[v];
  });
}

}  // namespace rosmill::core::io
