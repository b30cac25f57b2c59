#include "rosmill/testing/wavy_solid.hpp"

#include <cmath>
#include <utility>

namespace rosmill::core {

std::vector<Vec3> wavy_solid_corners(int n, double length) {
  auto height = [&](int i, int j) {
    return 10.0 + 7.5 * std::sin(2 * M_PI * 5 * i / n) * std::cos(2 * M_PI * 4 * j / n);
  };
  auto top = [&](int i, int j) { return Vec3(length * i / n, length * j / n, height(i, j)); };
  auto low = [&](int i, int j) { return Vec3(length * i / n, length * j / n, 0.0); };
  std::vector<Vec3> c;
  c.reserve(3 * (2 * size_t(n) * n + 12 * size_t(n)));
  auto tri = [&](const Vec3& a, const Vec3& b, const Vec3& d) {
    c.push_back(a);
    c.push_back(b);
    c.push_back(d);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      tri(top(i, j), top(i + 1, j), top(i + 1, j + 1));
      tri(top(i, j), top(i + 1, j + 1), top(i, j + 1));
    }
  // The rim walked counter-clockwise seen from +Z: walls face outwards, the bottom fan faces down.
  std::vector<std::pair<int, int>> ring;
  for (int k = 0; k < n; ++k) ring.emplace_back(k, 0);
  for (int k = 0; k < n; ++k) ring.emplace_back(n, k);
  for (int k = n; k > 0; --k) ring.emplace_back(k, n);
  for (int k = n; k > 0; --k) ring.emplace_back(0, k);
  const Vec3 centre(length / 2, length / 2, 0.0);
  for (size_t k = 0; k < ring.size(); ++k) {
    const auto [i0, j0] = ring[k];
    const auto [i1, j1] = ring[(k + 1) % ring.size()];
    tri(low(i0, j0), low(i1, j1), top(i1, j1));
    tri(low(i0, j0), top(i1, j1), top(i0, j0));
    tri(centre, low(i1, j1), low(i0, j0));
  }
  return c;
}

}  // namespace rosmill::core
