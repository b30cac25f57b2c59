#include "rosmill/plan/surface.hpp"

namespace rosmill {

void Surface::drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const {
  for (size_t i = 0; i < n; ++i) out[i] = drop(cutter, xy[i].x(), xy[i].y());
}

}  // namespace rosmill
