#include "rosmill/stock/height_field.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "rosmill/error.hpp"

namespace rosmill::core::stock {

GridSpec GridSpec::covering(const Vec2& min, const Vec2& max, double cell, size_t max_cells, const std::string& where,
                            size_t bytes_per_cell) {
  if (!(cell > 0) || !std::isfinite(cell))
    throw Error(where, "the cell size must be a positive number of mm, got " + std::to_string(cell));
  if (!min.allFinite() || !max.allFinite()) throw Error(where, "the area to cover is not finite");
  const Vec2 size = (max - min).cwiseMax(Vec2::Zero());
  const double nx = std::max(1.0, std::ceil(size.x() / cell - 1e-9));
  const double ny = std::max(1.0, std::ceil(size.y() / cell - 1e-9));
  if (nx * ny > static_cast<double>(max_cells)) {
    // The finest cell that fits, in two significant digits.
    const double fit = std::sqrt(std::max(size.x() * size.y(), 1e-300) / static_cast<double>(max_cells));
    const double unit = std::pow(10.0, std::floor(std::log10(fit)) - 1);
    double coarse = std::ceil(fit / unit - 1e-9) * unit;
    while (std::max(1.0, std::ceil(size.x() / coarse - 1e-9)) * std::max(1.0, std::ceil(size.y() / coarse - 1e-9)) >
           static_cast<double>(max_cells))
      coarse += unit;
    char finest[32];
    std::snprintf(finest, sizeof finest, "%g", coarse);
    char memory[64] = "";
    if (bytes_per_cell)
      std::snprintf(memory, sizeof memory, " (about %.3g MB)", nx * ny * static_cast<double>(bytes_per_cell) / 1e6);
    char what[300];
    std::snprintf(what, sizeof what, "a %.0f x %.0f mm area at %g mm cells would be %.3g cells%s, more than the %zu "
                  "allowed: use a cell of %s mm or more", size.x(), size.y(), cell, nx * ny, memory, max_cells, finest);
    throw Error(where, what);
  }
  GridSpec g;
  g.cell = cell;
  g.x0 = min.x();
  g.y0 = min.y();
  g.nx = static_cast<int>(nx);
  g.ny = static_cast<int>(ny);
  return g;
}

HeightField HeightField::box(const GridSpec& grid, double bottom_z, double top_z) {
  HeightField s;
  s.grid = grid;
  s.bottom = bottom_z;
  s.top.assign(grid.cells(), static_cast<float>(top_z));
  s.cut_by.assign(grid.cells(), kNoMove);
  return s;
}

}  // namespace rosmill::core::stock
