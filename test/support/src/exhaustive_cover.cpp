#include "rosmill/testing/exhaustive_cover.hpp"

#include <algorithm>
#include <map>
#include <vector>

namespace rosmill::core::testing {

ExhaustiveCover exhaustive_cover(const setups::SetupChoice& c, const segment::SurfacePatches& sp, double slack,
                                 uint64_t chosen) {
  const size_t n = c.candidates.size();
  // Per face: its area and what each candidate reaches of it.
  std::map<uint32_t, double> face_area;
  std::map<uint32_t, std::vector<double>> face_reach;
  for (size_t k = 0; k < c.samples.size(); ++k) {
    const uint32_t f = sp.label(c.samples.facets[k]);
    face_area[f] += c.samples.weights[k];
    face_reach[f].resize(n);
    for (size_t i = 0; i < n; ++i) face_reach[f][i] += (c.reached[k] >> i & 1) * c.samples.weights[k];
  }
  std::map<uint32_t, uint64_t> whole;
  for (const auto& [f, area] : face_area)
    for (size_t i = 0; i < n; ++i)
      if (face_reach[f][i] >= 0.995 * area) whole[f] |= uint64_t(1) << i;
  const auto cover = [&](uint64_t set) {
    double a = 0;
    for (size_t k = 0; k < c.samples.size(); ++k) {
      const uint64_t w = whole[sp.label(c.samples.facets[k])];
      a += (w ? (w & set) != 0 : (c.reached[k] & set) != 0) * c.samples.weights[k];
    }
    return a;
  };
  ExhaustiveCover e;
  const uint64_t all = n >= 64 ? ~uint64_t(0) : (uint64_t(1) << n) - 1;
  e.all = cover(all);
  e.of_chosen = cover(chosen);
  for (size_t size = 1; size <= n && e.fewest == 0; ++size)
    for (uint64_t set = 1; set <= all && set != 0; ++set)
      if (size_t(__builtin_popcountll(set)) == size) {
        const double a = cover(set);
        if (a >= e.all - slack) e.fewest = size, e.best = std::max(e.best, a);
      }
  return e;
}

}  // namespace rosmill::core::testing
