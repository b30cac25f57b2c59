#include "rosmill/geometry/vertex_welder.hpp"

#include <algorithm>

#include "rosmill/error.hpp"

namespace rosmill::core {
namespace {

constexpr size_t kBatch = 96;  // keys hashed and prefetched before any is probed

// Each word times its own odd constant: the product's top bits depend on every bit of the word, and the table
// index is taken from the top bits (coordinates often differ only in their high bits: 25.0 and 30.0).
template <class Word>
uint64_t key_hash(const std::array<Word, 3>& k) {
  return uint64_t(k[0]) * 0x9E3779B97F4A7C15ull ^ uint64_t(k[1]) * 0xC2B2AE3D27D4EB4Full ^
         uint64_t(k[2]) * 0x165667B19E3779F9ull;
}

template <class Word>
bool same_key(const std::array<Word, 3>& a, const std::array<Word, 3>& b) {
  return ((a[0] ^ b[0]) | (a[1] ^ b[1]) | (a[2] ^ b[2])) == 0;
}

}  // namespace

template <class Word>
ExactWelder<Word>::ExactWelder(size_t expected_vertices) {
  size_t slots = 64;
  while (2 * slots < 3 * expected_vertices) slots <<= 1;
  allocate(slots);
  keys_.resize(expected_vertices);
}

template <class Word>
void ExactWelder<Word>::allocate(size_t slots) {
  Slot free{};
  free.key[0] = kFree;
  slots_.assign(slots, free);
  mask_ = slots - 1;
  shift_ = 64 - __builtin_ctzll(slots);
}

template <class Word>
size_t ExactWelder<Word>::home(const Key& key) const {
  return size_t(key_hash(key) >> shift_);
}

template <class Word>
void ExactWelder<Word>::grow() {
  std::vector<Slot> old = std::move(slots_);
  allocate(2 * old.size());
  for (const Slot& s : old) {
    if (s.key[0] == kFree) continue;
    size_t i = home(s.key);
    while (slots_[i].key[0] != kFree) i = (i + 1) & mask_;
    slots_[i] = s;
  }
}

template <class Word>
void ExactWelder<Word>::make_room(size_t more) {
  if (size_ + more >= kAbsent) throw Error("mesh", "more than 4,294,967,294 distinct vertices");
  if (3 * (size_ + more) > 2 * slots_.size()) grow();  // at most two thirds full: short probe runs
  if (size_ + more > keys_.size()) keys_.resize(std::max(2 * keys_.size(), size_ + more));
}

template <class Word>
uint32_t ExactWelder<Word>::find(const Key& key, size_t i) const {
  for (;; i = (i + 1) & mask_) {
    const Slot& s = slots_[i];
    if (same_key(s.key, key)) return s.id;
    if (s.key[0] == kFree) return kAbsent;
  }
}

template <class Word>
void ExactWelder<Word>::add_many(const Key* keys, size_t n, uint32_t* ids) {
  size_t at[kBatch];
  for (size_t start = 0; start < n; start += kBatch) {
    const size_t m = std::min(kBatch, n - start);
    make_room(m);
    // The table's fields in locals: the probing loop then keeps them in registers.
    Slot* const slots = slots_.data();
    const size_t mask = mask_;
    Key* const stored = keys_.data();
    uint32_t size = uint32_t(size_);
    for (size_t k = 0; k < m; ++k) {
      at[k] = home(keys[start + k]);
      __builtin_prefetch(&slots[at[k]]);
    }
    for (size_t k = 0; k < m; ++k) {
      const Key& key = keys[start + k];
      for (size_t i = at[k];; i = (i + 1) & mask) {
        Slot& s = slots[i];
        if (same_key(s.key, key)) {
          ids[start + k] = s.id;
          break;
        }
        if (s.key[0] == kFree) {
          s.key = key;
          s.id = size;
          stored[size] = key;
          ids[start + k] = size++;
          break;
        }
      }
    }
    size_ = size;
  }
}

template <class Word>
void ExactWelder<Word>::find_many(const Key* keys, size_t n, uint32_t* ids) const {
  size_t at[kBatch];
  for (size_t start = 0; start < n; start += kBatch) {
    const size_t m = std::min(kBatch, n - start);
    for (size_t k = 0; k < m; ++k) {
      at[k] = home(keys[start + k]);
      __builtin_prefetch(&slots_[at[k]]);
    }
    for (size_t k = 0; k < m; ++k) ids[start + k] = find(keys[start + k], at[k]);
  }
}

template class ExactWelder<uint32_t>;
template class ExactWelder<uint64_t>;

}  // namespace rosmill::core
