#include "rosmill/segment/coverage.hpp"

#include "rosmill/segment/setup_segmentation.hpp"

namespace rosmill::core::segment {
namespace {

// Area of the facets marked in `reached`.
double marked_area(const Mesh& mesh, const std::vector<uint8_t>& reached) {
  double area = 0.0;
  for (size_t f = 0; f < reached.size(); ++f)
    if (reached[f]) area += mesh.areas[f];
  return area;
}

}  // namespace

double coverage(const EgiSet& egis, const std::vector<SetupFilter>& setups) {
  const Mesh& mesh = egis.patches().mesh();
  const double total = egis.patches().total_area();
  if (!(total > 0.0)) return 0.0;
  std::vector<uint8_t> any(mesh.face_count(), 0);
  for (const SetupFilter& s : setups) {
    const std::vector<uint8_t> r = reachable_facets(egis, s);
    for (size_t f = 0; f < any.size(); ++f) any[f] |= r[f];
  }
  return marked_area(mesh, any) / total;
}

std::vector<SetupFilter> greedy_axis_cover(const EgiSet& egis) {
  const Mesh& mesh = egis.patches().mesh();
  const std::vector<SetupFilter>& candidates = axis_setups();
  std::vector<std::vector<uint8_t>> reach;
  for (const SetupFilter& s : candidates) reach.push_back(reachable_facets(egis, s));

  std::vector<uint8_t> covered(mesh.face_count(), 0);
  std::vector<bool> taken(candidates.size(), false);
  std::vector<SetupFilter> cover;
  for (;;) {
    // The setup adding the most area not reached yet; the first in axis_setups() order on a tie.
    size_t best = candidates.size();
    double best_gain = 0.0;
    for (size_t s = 0; s < candidates.size(); ++s) {
      if (taken[s]) continue;
      double gain = 0.0;
      for (size_t f = 0; f < covered.size(); ++f)
        if (reach[s][f] && !covered[f]) gain += mesh.areas[f];
      if (gain > best_gain) {
        best_gain = gain;
        best = s;
      }
    }
    if (best == candidates.size()) break;  // nothing left that any remaining setup reaches
    taken[best] = true;
    cover.push_back(candidates[best]);
    for (size_t f = 0; f < covered.size(); ++f) covered[f] |= reach[best][f];
  }
  return cover;
}

}  // namespace rosmill::core::segment
