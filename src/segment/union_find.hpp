// A disjoint-set forest over 0..n-1 in one flat array: the root of a set is its smallest member, so labels that
// come out of it are deterministic and follow the facet order. Path halving keeps finds short without recursion.
#pragma once
#include <cstdint>
#include <numeric>
#include <vector>

namespace rosmill::core::segment::detail {

class UnionFind {
 public:
  explicit UnionFind(size_t n = 0) { reset(n); }

  void reset(size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), 0u);
  }
  size_t size() const { return parent_.size(); }

  uint32_t find(uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }

  // Joins the sets of a and b; returns the root of the joined set (the smaller of the two roots).
  uint32_t unite(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return a;
    if (a < b) {
      parent_[b] = a;
      return a;
    }
    parent_[a] = b;
    return b;
  }

 private:
  std::vector<uint32_t> parent_;
};

}  // namespace rosmill::core::segment::detail
