#include "rosmill/scan/point_index.hpp"

#include <limits>

#include <nanoflann.hpp>

#include "rosmill/error.hpp"

namespace rosmill::core::scan {
namespace {

struct Points {
  const std::vector<Vec3>& points;
  size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(size_t i, size_t d) const { return points[i][int(d)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};

// nanoflann's result set for one neighbour that never lets the search look further than the reach: the tree
// prunes every cell beyond the best distance so far, which starts at the reach.
struct NearestWithin {
  double best_sq;
  size_t index = 0;
  bool found = false;
  double worstDist() const { return best_sq; }
  bool full() const { return found; }
  bool addPoint(double sq, size_t i) {
    if (sq < best_sq) {
      best_sq = sq;
      index = i;
      found = true;
    }
    return true;
  }
};

}  // namespace

struct PointIndex::Tree {
  explicit Tree(const std::vector<Vec3>& points)
      : adaptor{points}, index(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(12)) {}
  Points adaptor;
  // nanoflann 1.4 builds the tree in its constructor.
  nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Points>, Points, 3, size_t> index;
};

PointIndex::PointIndex(std::vector<Vec3> points) : points_(std::move(points)) {
  if (points_.empty()) throw Error("point index", "no point to index");
  for (const Vec3& p : points_)
    if (!p.allFinite()) throw Error("point index", "a point is NaN or infinite");
  tree_ = std::make_unique<Tree>(points_);
}

PointIndex::~PointIndex() = default;

bool PointIndex::nearest(const Vec3& p, double reach, size_t& index, double& squared) const {
  return nearest(p, reach, no_hint, index, squared);
}

bool PointIndex::nearest(const Vec3& p, double reach, size_t hint, size_t& index, double& squared) const {
  NearestWithin result{reach * reach};
  if (hint < points_.size()) result.addPoint((points_[hint] - p).squaredNorm(), hint);
  tree_->index.findNeighbors(result, p.data(), nanoflann::SearchParams());
  if (!result.found) return false;
  index = result.index;
  squared = result.best_sq;
  return true;
}

size_t PointIndex::nearest_k(const Vec3& p, size_t k, size_t* indices, double* squared) const {
  return tree_->index.knnSearch(p.data(), k, indices, squared);
}

}  // namespace rosmill::core::scan
