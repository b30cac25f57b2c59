#include "rosmill/plan/drop_grid.hpp"

#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/work_bound.hpp"

namespace rosmill::core {

DropGrid grid_over(const Box3& box, double radius, double step) {
  if (!(step > 0) || !std::isfinite(step)) throw Error("--spacing", "must be a positive number");
  if (box.empty()) throw Error("grid", "the model is empty");
  DropGrid g;
  g.step = step;
  g.x0 = box.min.x() - radius;
  g.y0 = box.min.y() - radius;
  // Exactly the documented formula, in the same order of operations, so that any reader of it counts the same.
  const double nx = std::floor((box.max.x() + radius - (box.min.x() - radius)) / step) + 1;
  const double ny = std::floor((box.max.y() + radius - (box.min.y() - radius)) / step) + 1;
  check_work("--spacing", {nx * ny, nx * ny, count_text(nx, "columns") + " x " + count_text(ny, "rows")},
             box.size().x(), box.size().y());
  g.nx = static_cast<size_t>(nx);
  g.ny = static_cast<size_t>(ny);
  return g;
}

std::vector<Vec3> drop_grid(const Surface& surface, const Cutter& cutter, const DropGrid& grid, double floor) {
  const size_t n = grid.size();
  std::vector<Vec2> xy(n);
  for (size_t k = 0; k < n; ++k) xy[k] = grid.point(k);
  std::vector<Drop> drops(n);
  surface.drop_many(cutter, xy.data(), n, drops.data());
  std::vector<Vec3> out(n);
  for (size_t k = 0; k < n; ++k) out[k] = Vec3(xy[k].x(), xy[k].y(), std::max(drops[k].z, floor));
  return out;
}

}  // namespace rosmill::core
