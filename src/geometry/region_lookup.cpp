#include "rosmill/geometry/region_lookup.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "rosmill/geometry/grid_flood.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/segment_distance.hpp"

namespace rosmill::core {
namespace {

constexpr double kOnEdge = 1e-6;  // mm: a point this close to an edge is on it (Clipper's unit, 1 nm)

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Whether the segment from c to p crosses the edge a-b; an end of the edge exactly on the line c-p counts on one
// side only, so a path through a vertex where two edges meet crosses one of them or neither, as it should.
bool crosses(const Vec2& c, const Vec2& p, const Vec2& a, const Vec2& b) {
  if ((orient(c, p, a) > 0) == (orient(c, p, b) > 0)) return false;
  return (orient(a, b, c) > 0) != (orient(a, b, p) > 0);
}

}  // namespace

RegionLookup::RegionLookup(const clip::Paths& region, double cell) : cell_(cell) {
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
  for (const clip::Path& path : region)
    for (const auto& q : path) {
      const Vec2 v = clip::from_point(q);
      lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    }
  if (!(lo.x() <= hi.x())) return;  // empty: nothing is inside
  x0_ = lo.x() - cell, y0_ = lo.y() - cell;
  nx_ = static_cast<long>(std::ceil((hi.x() - lo.x()) / cell)) + 2;
  ny_ = static_cast<long>(std::ceil((hi.y() - lo.y()) / cell)) + 2;
  // Cells are indexed in 32 bits (the edges' lists); a grid that large would not fit in memory anyway.
  if (!(double(nx_) * double(ny_) < 1e9))
    throw Error("region lookup", "a grid of " + std::to_string(nx_) + " x " + std::to_string(ny_) + " cells of " +
                                     std::to_string(cell) + " mm over the region is too large (at most 1e9 cells)");
  state_.assign(size_t(nx_) * size_t(ny_), kOut);
  // The cells each edge touches, as (cell, edge) pairs gathered and then grouped by cell.
  std::vector<std::pair<uint32_t, uint32_t>> touched;
  for (const clip::Path& path : region)
    for (size_t k = 0; k < path.size(); ++k) {
      const Vec2 a = clip::from_point(path[k]), b = clip::from_point(path[(k + 1) % path.size()]);
      if (a == b) continue;
      const uint32_t id = static_cast<uint32_t>(edges_.size());
      edges_.push_back({a, b});
      // Row by row, the span of x the edge covers within the row's band, widened by a hair so that cells it only
      // touches count too (a cell counted for nothing costs a test, a cell missed a wrong answer).
      const double eps = 1e-9 * cell;
      const long j0 = std::max(0L, static_cast<long>(std::floor((std::min(a.y(), b.y()) - y0_ - eps) / cell)));
      const long j1 = std::min(ny_ - 1, static_cast<long>(std::floor((std::max(a.y(), b.y()) - y0_ + eps) / cell)));
      for (long j = j0; j <= j1; ++j) {
        const double ylo = y0_ + j * cell, yhi = ylo + cell;
        double xlo = std::min(a.x(), b.x()), xhi = std::max(a.x(), b.x());
        if (a.y() != b.y()) {
          const auto x_at = [&](double y) { return a.x() + (b.x() - a.x()) * (y - a.y()) / (b.y() - a.y()); };
          const double ya = std::clamp(ylo, std::min(a.y(), b.y()), std::max(a.y(), b.y()));
          const double yb = std::clamp(yhi, std::min(a.y(), b.y()), std::max(a.y(), b.y()));
          xlo = std::min(x_at(ya), x_at(yb)), xhi = std::max(x_at(ya), x_at(yb));
        }
        const long i0 = std::max(0L, static_cast<long>(std::floor((xlo - x0_ - eps) / cell)));
        const long i1 = std::min(nx_ - 1, static_cast<long>(std::floor((xhi - x0_ + eps) / cell)));
        for (long i = i0; i <= i1; ++i) touched.push_back({static_cast<uint32_t>(j * nx_ + i), id});
      }
    }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  first_.assign(state_.size() + 1, 0);
  for (const auto& [c, id] : touched) ++first_[c + 1], state_[c] = kCrossed;
  for (size_t c = 0; c < state_.size(); ++c) first_[c + 1] += first_[c];
  edge_ids_.resize(touched.size());
  for (size_t k = 0; k < touched.size(); ++k) edge_ids_[k] = touched[k].second;
  centre_in_.assign(state_.size(), 0);
  for (size_t c = 0; c < state_.size(); ++c) {
    if (state_[c] != kCrossed) continue;
    const Vec2 centre = centre_of(c);
    centre_in_[c] = clip::contains(region, centre);
    // A centre on the boundary is no reference for the crossings: that cell asks the region itself.
    for (uint32_t k = first_[c]; k < first_[c + 1]; ++k)
      if (segment_distance(centre, edges_[edge_ids_[k]].a, edges_[edge_ids_[k]].b) <= kOnEdge) state_[c] = kExact;
  }
  if (std::find(state_.begin(), state_.end(), kExact) != state_.end()) region_ = region;
  classify_open_cells(region);
}

// Cells no edge touches, joined across their sides, lie all inside or all outside (no boundary parts them): one
// exact test per such group.
void RegionLookup::classify_open_cells(const clip::Paths& region) {
  std::vector<uint8_t> seen(state_.size(), 0);
  std::vector<size_t> group, open;
  for (size_t start = 0; start < state_.size(); ++start) {
    if (seen[start] || state_[start] >= kCrossed) continue;
    group.clear();
    flood_cells(nx_, ny_, start, seen, open, [&](size_t c) { return state_[c] < kCrossed; },
                [&](size_t c) { group.push_back(c); });
    const uint8_t state = clip::contains(region, centre_of(start)) ? kIn : kOut;
    for (size_t c : group) state_[c] = state;
  }
}

Vec2 RegionLookup::centre_of(size_t c) const {
  return {x0_ + (double(long(c) % nx_) + 0.5) * cell_, y0_ + (double(long(c) / nx_) + 0.5) * cell_};
}

bool RegionLookup::contains(const Vec2& p) const {
  const double fx = (p.x() - x0_) / cell_, fy = (p.y() - y0_) / cell_;
  if (!(fx >= 0 && fy >= 0 && fx < double(nx_) && fy < double(ny_))) return false;
  const size_t c = size_t(static_cast<long>(fy)) * size_t(nx_) + size_t(static_cast<long>(fx));
  if (state_[c] < kCrossed) return state_[c] == kIn;
  if (state_[c] == kExact) return clip::contains(region_, p);
  const Vec2 centre = centre_of(c);
  bool in = centre_in_[c];
  for (uint32_t k = first_[c]; k < first_[c + 1]; ++k) {
    const Edge& e = edges_[edge_ids_[k]];
    if (segment_distance(p, e.a, e.b) <= kOnEdge) return true;
    if (crosses(centre, p, e.a, e.b)) in = !in;
  }
  return in;
}

}  // namespace rosmill::core
