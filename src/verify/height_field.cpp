#include "rosmill/verify/height_field.hpp"

#include <algorithm>

#include "rosmill/error.hpp"

namespace rosmill::verify {

GridSpec GridSpec::covering(const Vec2& min, const Vec2& max, double cell) {
  if (!(cell > 0)) throw Error("--resolution", "the cell size must be positive");
  GridSpec g;
  g.cell = cell;
  g.x0 = min.x();
  g.y0 = min.y();
  const double nx = std::ceil((max.x() - min.x()) / cell - 1e-9), ny = std::ceil((max.y() - min.y()) / cell - 1e-9);
  if (nx * ny > 400e6) throw Error("--resolution", "the grid would have more than 400 million cells");
  g.nx = std::max(1, static_cast<int>(nx));
  g.ny = std::max(1, static_cast<int>(ny));
  return g;
}

Stock Stock::box(const GridSpec& grid, double bottom_z, double top_z) {
  Stock s;
  s.grid = grid;
  s.bottom = bottom_z;
  s.top.assign(grid.cells(), static_cast<float>(top_z));
  s.cut_by.assign(grid.cells(), kNoMove);
  return s;
}

}  // namespace rosmill::verify
