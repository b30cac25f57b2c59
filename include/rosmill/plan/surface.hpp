// The seam between geometry and planning (../DESIGN): "where does this cutter touch down at (x, y)?".
// A mesh answers from its triangles, a point cloud from its points; every strategy is written against this.
#pragma once
#include <cstddef>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/types.hpp"

namespace rosmill {

struct Drop {
  double z = 0.0;       // tip height of the cutter at its lowest position that touches the surface
  bool touched = false; // false: nothing lies under the cutter's footprint (z is then the surface's floor)
};

class Surface {
 public:
  virtual ~Surface() = default;
  virtual Box3 bounds() const = 0;
  // Lowest tip height for the cutter with its axis at (x, y) that does not go into the surface. Thread-safe,
  // no allocation: strategies call it from both cores.
  virtual Drop drop(const Cutter& cutter, double x, double y) const = 0;
  // Batch form: z for n points; the default loops over drop(). Implementations parallelise.
  virtual void drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const;
};

}  // namespace rosmill
