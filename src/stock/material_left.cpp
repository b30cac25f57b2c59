#include "rosmill/stock/material_left.hpp"

#include <cmath>

namespace rosmill::core::stock {

std::vector<float> material_left_at(const InProcessStock& stock, const Mesh& design, const SetupFrame& setup,
                                    const std::vector<Vec3>& points) {
  const GridSpec g = stock.setup_grid(setup);
  const std::vector<float> above = stock.material_above(design, setup);
  std::vector<float> left(points.size(), NAN);
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec3 p = setup.to_setup_frame(points[k]);
    const double i = std::floor((p.x() - g.x0) / g.cell), j = std::floor((p.y() - g.y0) / g.cell);
    if (!(i >= 0 && i < g.nx && j >= 0 && j < g.ny)) continue;
    left[k] = above[g.index(int(i), int(j))];
  }
  return left;
}

}  // namespace rosmill::core::stock
