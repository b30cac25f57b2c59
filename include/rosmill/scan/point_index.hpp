// A k-d tree over a point set (nanoflann, double precision): the nearest point within a reach and the k nearest
// points. Built once and queried from many threads at once: a query is const and allocates nothing, which keeps
// ICP's thousands of queries per step cheap (one tree per fixed surface, whatever the number of alignments).
#pragma once
#include <cstddef>
#include <memory>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::scan {

class PointIndex {
 public:
  // Keeps its own copy of the points. Throws Error when there is none or one is not finite.
  explicit PointIndex(std::vector<Vec3> points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  // The nearest point strictly within `reach` mm of p: true with its index and squared distance, false when none.
  bool nearest(const Vec3& p, double reach, size_t& index, double& squared) const;
  // The same, with a hint: the index of a point likely near p (an iteration's answer for the same query point at
  // the step before). The search starts from the hint's distance, which prunes most of the tree; the answer is
  // the same nearest point. A hint of no_hint or out of range is ignored.
  static constexpr size_t no_hint = size_t(-1);
  bool nearest(const Vec3& p, double reach, size_t hint, size_t& index, double& squared) const;
  // The k nearest points (all of them when there are fewer), nearest first, into indices[0..) and squared[0..);
  // returns how many.
  size_t nearest_k(const Vec3& p, size_t k, size_t* indices, double* squared) const;

  const std::vector<Vec3>& points() const { return points_; }

 private:
  struct Tree;
  std::vector<Vec3> points_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace rosmill::core::scan
