#include "rosmill/plan/levels.hpp"

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
