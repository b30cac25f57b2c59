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
  first_slots_ = slots;
  keys_.reset(new Key[expected_vertices]);  // default-initialised: not written
  capacity_ = expected_vertices;
}

template <class Word>
void ExactWelder<Word>::allocate(size_t slots) {
  slots_.assign(slots, Slot{0, kAbsent});
  mask_ = slots - 1;
  shift_ = 64 - __builtin_ctzll(slots);
}

template <class Word>
uint64_t ExactWelder<Word>::hash(const Key& key) const {
  return key_hash(key);
}

template <class Word>
void ExactWelder<Word>::grow() {
  std::vector<Slot> old = std::move(slots_);
  allocate(2 * old.size());
  for (const Slot& s : old) {
    if (s.id == kAbsent) continue;
    size_t i = home(hash(keys_[s.id]));
    while (slots_[i].id != kAbsent) i = (i + 1) & mask_;
    slots_[i] = s;
  }
}

template <class Word>
void ExactWelder<Word>::make_room(size_t more) {
  if (size_ + more >= kAbsent) throw Error("mesh", "more than 4,294,967,294 distinct vertices");
  if (slots_.empty()) allocate(first_slots_);
  if (3 * (size_ + more) > 2 * slots_.size()) grow();  // at most two thirds full: short probe runs
  if (size_ + more > capacity_) {
    capacity_ = std::max(2 * capacity_, size_ + more);
    std::unique_ptr<Key[]> grown(new Key[capacity_]);
    std::copy(keys_.get(), keys_.get() + size_, grown.get());
    keys_ = std::move(grown);
  }
}

template <class Word>
uint32_t ExactWelder<Word>::find(const Key& key, uint64_t h) const {
  const uint32_t tag = uint32_t(h);
  for (size_t i = home(h);; i = (i + 1) & mask_) {
    const Slot& s = slots_[i];
    if (s.id == kAbsent) return kAbsent;
    if (s.tag == tag && same_key(keys_[s.id], key)) return s.id;
  }
}

template <class Word>
void ExactWelder<Word>::add_many(const Key* keys, size_t n, uint32_t* ids) {
  uint64_t hashes[kBatch];
  for (size_t start = 0; start < n; start += kBatch) {
    const size_t m = std::min(kBatch, n - start);
    make_room(m);
    // The table's fields in locals: the probing loop then keeps them in registers.
    Slot* const slots = slots_.data();
    const size_t mask = mask_;
    Key* const stored = keys_.get();
    uint32_t size = uint32_t(size_);
    for (size_t k = 0; k < m; ++k) {
      hashes[k] = hash(keys[start + k]);
      __builtin_prefetch(&slots[home(hashes[k])]);
    }
    for (size_t k = 0; k < m; ++k) {
      const Key& key = keys[start + k];
      const uint32_t tag = uint32_t(hashes[k]);
      for (size_t i = home(hashes[k]);; i = (i + 1) & mask) {
        Slot& s = slots[i];
        if (s.id == kAbsent) {
          s = Slot{tag, size};
          stored[size] = key;
          ids[start + k] = size++;
          break;
        }
        if (s.tag == tag && same_key(stored[s.id], key)) {
          ids[start + k] = s.id;
          break;
        }
      }
    }
    size_ = size;
  }
}

template <class Word>
void ExactWelder<Word>::find_many(const Key* keys, size_t n, uint32_t* ids) const {
  if (slots_.empty()) {  // nothing added yet
    std::fill(ids, ids + n, kAbsent);
    return;
  }
  uint64_t hashes[kBatch];
  for (size_t start = 0; start < n; start += kBatch) {
    const size_t m = std::min(kBatch, n - start);
    for (size_t k = 0; k < m; ++k) {
      hashes[k] = hash(keys[start + k]);
      __builtin_prefetch(&slots_[home(hashes[k])]);
    }
    for (size_t k = 0; k < m; ++k) ids[start + k] = find(keys[start + k], hashes[k]);
  }
}

template class ExactWelder<uint32_t>;
template class ExactWelder<uint64_t>;

}  // namespace rosmill::core
