#include "rosmill/geometry/vertex_welder.hpp"

#include <algorithm>
#include <cstring>

#include "rosmill/error.hpp"

namespace rosmill {
namespace {

uint64_t bits_of(double v) {
  v += 0.0;  // -0 + 0 is +0: both zeros hash alike (they compare equal below)
  uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// STL coordinates are float32 values widened to double, so their low 29 bits are zero: each coordinate is
// multiplied by its own odd constant (spreading its bits upwards), and the sum is folded so that the table
// index (the low bits) depends on all of them.
uint64_t position_hash(const Vec3& p) {
  uint64_t h = bits_of(p.x()) * 0x9E3779B97F4A7C15ull + bits_of(p.y()) * 0xC2B2AE3D27D4EB4Full +
               bits_of(p.z()) * 0x165667B19E3779F9ull;
  h ^= h >> 32;
  h *= 0xD6E8FEB86659FD93ull;
  return h ^ (h >> 29);
}

size_t power_of_two_at_least(size_t n) {
  size_t c = 64;
  while (c < n) c <<= 1;
  return c;
}

}  // namespace

VertexWelder::VertexWelder(size_t expected_vertices) {
  slots_.assign(power_of_two_at_least(2 * expected_vertices), Slot{0, kEmpty});
  mask_ = slots_.size() - 1;
  vertices_.reserve(expected_vertices);
}

uint32_t VertexWelder::insert(const Vec3& p, uint64_t hash) {
  const uint32_t tag = uint32_t(hash >> 32);
  for (uint64_t i = hash & mask_;; i = (i + 1) & mask_) {
    Slot& s = slots_[i];
    if (s.id == kEmpty) {
      if (vertices_.size() >= kEmpty) throw Error("mesh", "more than 4,294,967,294 distinct vertices");
      s = Slot{tag, uint32_t(vertices_.size())};
      vertices_.push_back(p);
      return s.id;
    }
    if (s.tag == tag && vertices_[s.id] == p) return s.id;
  }
}

void VertexWelder::grow() {
  std::vector<Slot> old = std::move(slots_);
  slots_.assign(2 * old.size(), Slot{0, kEmpty});
  mask_ = slots_.size() - 1;
  for (const Slot& s : old) {
    if (s.id == kEmpty) continue;
    const uint64_t hash = position_hash(vertices_[s.id]);
    uint64_t i = hash & mask_;
    while (slots_[i].id != kEmpty) i = (i + 1) & mask_;
    slots_[i] = s;
  }
}

void VertexWelder::add_many(const Vec3* points, size_t n, uint32_t* ids) {
  constexpr size_t kBatch = 16;
  uint64_t hash[kBatch];
  for (size_t start = 0; start < n; start += kBatch) {
    const size_t m = std::min(kBatch, n - start);
    // At most half full after this batch, so probe sequences stay short.
    if (2 * (vertices_.size() + m) > slots_.size()) grow();
    for (size_t k = 0; k < m; ++k) {
      hash[k] = position_hash(points[start + k]);
      __builtin_prefetch(&slots_[hash[k] & mask_]);
    }
    for (size_t k = 0; k < m; ++k) ids[start + k] = insert(points[start + k], hash[k]);
  }
}

}  // namespace rosmill
