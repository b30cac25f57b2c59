// A point cloud in the core: points in millimetres, finite only (readers drop NaN and infinite points).
#pragma once
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

struct PointCloud {
  std::vector<Vec3> points;
  Box3 bbox;  // of `points`

  void recompute_bbox() {
    bbox = Box3{};
    for (const Vec3& p : points) bbox.add(p);
  }
};

}  // namespace rosmill::core
