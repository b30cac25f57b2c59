#include "rosmill/scan/covered_share.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "rosmill/scan/point_index.hpp"

namespace rosmill::core::scan {

double covered_share(const std::vector<Vec3>& queries, const std::vector<Vec3>& cloud, double radius) {
  if (queries.empty() || cloud.empty()) return 0;
  const PointIndex index(cloud);
  const size_t covered = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, queries.size(), 1024), size_t(0),
      [&](const tbb::blocked_range<size_t>& range, size_t count) {
        size_t unused_index;
        double unused_sq;
        for (size_t i = range.begin(); i != range.end(); ++i)
          if (index.nearest(queries[i], radius, unused_index, unused_sq)) ++count;
        return count;
      },
      [](size_t a, size_t b) { return a + b; });
  return double(covered) / double(queries.size());
}

}  // namespace rosmill::core::scan
