// Exact vertex welding: one vertex per distinct corner position, numbered in order of first appearance (which
// keeps the locality of the file's triangle order for every later pass).
//
// A position is welded by its coordinates' bit patterns (a weld key): float32 words straight from a binary STL,
// float64 words for anything parsed into doubles. -0 is folded to +0 first, so the two zeros weld; keys are
// never NaN (callers refuse non-finite coordinates before welding).
//
// A flat open-addressing table of (hash tag, vertex id) slots, at most two thirds full: no allocation per corner,
// a probe compares 32 bits of the key's hash inside its slot and reads the key itself only when they agree, and
// add_many() prefetches the slots of a batch before probing them, so the table's cache misses overlap. This is
// the hot loop of STL loading (about 6 corners per vertex). A slot is 8 bytes, not the key's 12 or 24 and an id:
// a table of a million slots (half of a 2M-triangle file) is then 8 MB rather than 16, and fresh memory is what a
// large load pays most for on a virtual machine (heap_reuse.hpp).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <type_traits>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

template <class Word>
class ExactWelder {
 public:
  using Key = std::array<Word, 3>;
  static constexpr uint32_t kAbsent = 0xffffffffu;

  // `expected_vertices` sizes the keys and the table (both grow when exceeded). The keys are allocated here, the
  // table when the first key is added: a caller that makes several welders, then adds to them, has their tables
  // side by side on the heap, to be released together (release_table).
  explicit ExactWelder(size_t expected_vertices = 1024);

  // The vertex id of each of `n` keys, adding the new ones.
  void add_many(const Key* keys, size_t n, uint32_t* ids);
  // The vertex id of each of `n` keys, or kAbsent; reads only, so several threads may call it at once.
  void find_many(const Key* keys, size_t n, uint32_t* ids) const;

  size_t size() const { return size_; }
  // The distinct keys, indexed by vertex id: keys()[0, size()).
  const Key* keys() const { return keys_.get(); }
  // Frees the table once no key is to be added or found any more; the keys stay.
  void release_table() { std::vector<Slot>().swap(slots_); }

 private:
  struct Slot {
    uint32_t tag;  // the key's hash's low 32 bits (the slot's index is taken from its top bits)
    uint32_t id;   // kAbsent when the slot is free
  };

  uint64_t hash(const Key& key) const;
  size_t home(uint64_t hash) const { return size_t(hash >> shift_); }
  uint32_t find(const Key& key, uint64_t hash) const;
  void allocate(size_t slots);
  void grow();
  void make_room(size_t more);

  std::vector<Slot> slots_;
  size_t mask_ = 0;
  int shift_ = 0;  // the table index is the hash's top bits
  // Room for `capacity_` keys ahead of size_ (no reallocation inside the probing loop), left unwritten until a
  // key is stored: its pages are first touched by the thread that welds, not all at once by the one that made it.
  std::unique_ptr<Key[]> keys_;
  size_t capacity_ = 0;
  size_t size_ = 0;
  size_t first_slots_ = 0;  // the table's size when it is made
};

using FloatWelder = ExactWelder<uint32_t>;   // binary STL corners
using DoubleWelder = ExactWelder<uint64_t>;  // corners parsed into doubles

// A coordinate's weld word: its bit pattern with -0 folded to +0 (without a branch, so loops over many
// coordinates vectorize).
template <class Scalar>
auto weld_word(Scalar v) {
  using Word = std::conditional_t<sizeof(Scalar) == sizeof(uint32_t), uint32_t, uint64_t>;
  static_assert(std::is_floating_point_v<Scalar> && sizeof(Scalar) == sizeof(Word), "float or double");
  Word b;
  std::memcpy(&b, &v, sizeof b);
  return Word(b & (Word(0) - Word((b << 1) != 0)));
}
inline DoubleWelder::Key weld_key(const Vec3& p) { return {weld_word(p.x()), weld_word(p.y()), weld_word(p.z())}; }

// The position a key stands for.
template <class Word>
Vec3 key_position(const std::array<Word, 3>& key) {
  using Scalar = std::conditional_t<sizeof(Word) == sizeof(float), float, double>;
  Scalar c[3];
  std::memcpy(c, key.data(), sizeof c);
  return Vec3(c[0], c[1], c[2]);
}

}  // namespace rosmill::core
