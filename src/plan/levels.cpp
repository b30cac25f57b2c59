#include "rosmill/plan/levels.hpp"

#include "rosmill/plan/drop_grid.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace rosmill::core {

std::vector<double> flat_heights(std::vector<double> cl_heights, size_t min_count, double floor) {
  constexpr double kSame = 1e-6;
  std::sort(cl_heights.begin(), cl_heights.end(), std::greater<double>());
  std::vector<double> flats;
  for (size_t i = 0; i < cl_heights.size();) {
    size_t j = i;
    while (j < cl_heights.size() && cl_heights[i] - cl_heights[j] <= kSame) ++j;
    if (j - i >= std::max<size_t>(min_count, 1) && cl_heights[i] > floor + kSame && std::isfinite(cl_heights[i]))
      flats.push_back(cl_heights[i]);
    i = j;
  }
  return flats;
}

std::vector<double> flat_face_heights(const Surface& surface, const PlanFrame& f) {
  constexpr double kSame = 1e-6;
  const DropGrid g = grid_over(f.part, 0, std::max(0.5 * f.cutter.radius(), 0.5));
  std::vector<double> h;
  for (const Vec3& p : drop_grid(surface, f.drop_cutter, g, f.part.min.z())) h.push_back(p.z() + f.allowance);
  const auto same = [&](size_t a, size_t b) { return std::abs(h[a] - h[b]) <= kSame; };
  std::vector<double> plateaus;
  for (size_t j = 0; j < g.ny; ++j)
    for (size_t i = 0; i < g.nx; ++i) {
      const size_t k = j * g.nx + i;
      const bool row = (i > 0 && same(k, k - 1)) || (i + 1 < g.nx && same(k, k + 1));
      const bool column = (j > 0 && same(k, k - g.nx)) || (j + 1 < g.ny && same(k, k + g.nx));
      if (row && column) plateaus.push_back(h[k]);
    }
  const double floor = f.part.min.z() + f.allowance;
  return flat_heights(std::move(plateaus), 4, floor);
}

std::vector<double> roughing_levels(double top, double floor, double stepdown, const std::vector<double>& flats,
                                    double merge) {
  std::vector<double> levels;
  for (double f : flats)
    if (f < top - 1e-9 && f > floor + 1e-9) levels.push_back(f);
  for (double z = top - stepdown; z > floor + 1e-9; z -= stepdown) {
    const bool cut_by_flat = std::any_of(flats.begin(), flats.end(), [&](double f) { return z >= f && z - f <= merge; });
    if (!cut_by_flat) levels.push_back(z);
  }
  levels.push_back(floor);
  std::sort(levels.begin(), levels.end(), std::greater<double>());
  levels.erase(std::unique(levels.begin(), levels.end(), [](double a, double b) { return a - b < 1e-9; }),
               levels.end());
  return levels;
}

}  // namespace rosmill::core
