#include "rosmill/scan/covered_share.hpp"

#include "rosmill/parallel.hpp"
#include "rosmill/scan/point_index.hpp"

namespace rosmill::core::scan {

double covered_share(const std::vector<Vec3>& queries, const std::vector<Vec3>& cloud, double radius) {
  if (queries.empty() || cloud.empty()) return 0;
  const PointIndex index(cloud);
  const size_t covered = reduce_pieces(
      size_t(0), queries.size(), size_t(1024), size_t(0),
      [&](size_t begin, size_t end, size_t count) {
        size_t unused_index;
        double unused_sq;
        for (size_t i = begin; i != end; ++i)
          if (index.nearest(queries[i], radius, unused_index, unused_sq)) ++count;
        return count;
      },
      [](size_t a, size_t b) { return a + b; });
  return double(covered) / double(queries.size());
}

}  // namespace rosmill::core::scan
