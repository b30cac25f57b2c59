// Exact vertex welding: one vertex per distinct corner position, numbered in order of first appearance (which
// keeps the locality of the file's triangle order for every later pass).
//
// A flat open-addressing table of (hash tag, vertex id) slots, grown at half load: no allocation per corner, and
// add_many() prefetches the slots of a batch before probing them, so the table's cache misses overlap. This is
// the hot loop of STL loading (about 6 corners per vertex).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill {

class VertexWelder {
 public:
  // `expected_vertices` sizes the table (it grows when exceeded).
  explicit VertexWelder(size_t expected_vertices = 1024);

  // The vertex id of each of `n` points (finite coordinates; -0 and +0 are the same position).
  void add_many(const Vec3* points, size_t n, uint32_t* ids);
  uint32_t add(const Vec3& p) {
    uint32_t id;
    add_many(&p, 1, &id);
    return id;
  }

  const std::vector<Vec3>& vertices() const { return vertices_; }
  std::vector<Vec3> take_vertices() { return std::move(vertices_); }

 private:
  struct Slot {
    uint32_t tag;  // high bits of the hash, to skip most coordinate comparisons
    uint32_t id;   // kEmpty when free
  };
  static constexpr uint32_t kEmpty = 0xffffffffu;

  uint32_t insert(const Vec3& p, uint64_t hash);
  void grow();

  std::vector<Slot> slots_;
  uint64_t mask_ = 0;
  std::vector<Vec3> vertices_;
};

}  // namespace rosmill
