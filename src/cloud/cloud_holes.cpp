#include "rosmill/cloud/cloud_holes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rosmill/error.hpp"

namespace rosmill::core {

double auto_hole_cell(const CloudGrid& grid) {
  const Vec3 size = grid.bounds().size();
  const double area = std::max(size.x() * size.y(), 1e-6);
  // Probe cells of about 64 points (on average over the plan box).
  const double r50 = sampling_radius(grid, grid.regridded(4 * auto_grid_cell(grid.size(), area)), 0.5);
  if (r50 > 0) return std::max(kHoleCellRadii * r50, 1e-3);
  // A thin cloud (no probe cell inside the data): from the nearest-neighbour spacing instead.
  return std::max(3.5 * spacing_quantile(grid, 0.95), 1e-3);
}

HolePolicy parse_hole_policy(const std::string& text, const std::string& where) {
  if (text == "bridge") return HolePolicy::Bridge;
  if (text == "skip") return HolePolicy::Skip;
  throw Error(where, "unknown hole policy '" + text + "' (expected bridge or skip)");
}

namespace {

constexpr uint8_t kFilled = 0, kEmpty = 1, kOutside = 2, kHole = 3;

// Flood fill over 4-connected empty cells starting at `seed`, marking them `mark`; returns the cells visited.
std::vector<size_t> flood(const CloudGrid& g, std::vector<uint8_t>& state, size_t seed, uint8_t mark) {
  std::vector<size_t> cells, stack{seed};
  state[seed] = mark;
  while (!stack.empty()) {
    const size_t c = stack.back();
    stack.pop_back();
    cells.push_back(c);
    const int cx = int(c % size_t(g.nx())), cy = int(c / size_t(g.nx()));
    const int nb[4][2] = {{cx - 1, cy}, {cx + 1, cy}, {cx, cy - 1}, {cx, cy + 1}};
    for (const auto& n : nb) {
      if (n[0] < 0 || n[1] < 0 || n[0] >= g.nx() || n[1] >= g.ny()) continue;
      const size_t k = g.index(n[0], n[1]);
      if (state[k] != kEmpty) continue;
      state[k] = mark;
      stack.push_back(k);
    }
  }
  return cells;
}

// Highest point in the filled cells 8-adjacent to any cell of the hole.
double rim_height(const CloudGrid& g, const std::vector<size_t>& hole) {
  double z = -std::numeric_limits<double>::infinity();
  for (size_t c : hole) {
    const int cx = int(c % size_t(g.nx())), cy = int(c / size_t(g.nx()));
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = cx + dx, y = cy + dy;
        if (x < 0 || y < 0 || x >= g.nx() || y >= g.ny()) continue;
        z = std::max(z, g.zmax(g.index(x, y)));
      }
  }
  return z;
}

}  // namespace

HoleMap::HoleMap(const std::vector<Vec3>& points, double cell) : grid_(points, cell) {
  const size_t n = cells();
  std::vector<uint8_t> state(n, kFilled);
  for (size_t c = 0; c < n; ++c)
    if (grid_.count(c) == 0) {
      state[c] = kEmpty;
      ++empty_cells_;
    }
  if (empty_cells_ == 0) return;
  // Outside: everything reachable from the border.
  for (int x = 0; x < grid_.nx(); ++x)
    for (int y : {0, grid_.ny() - 1}) {
      const size_t c = grid_.index(x, y);
      if (state[c] == kEmpty) outside_cells_ += flood(grid_, state, c, kOutside).size();
    }
  for (int y = 0; y < grid_.ny(); ++y)
    for (int x : {0, grid_.nx() - 1}) {
      const size_t c = grid_.index(x, y);
      if (state[c] == kEmpty) outside_cells_ += flood(grid_, state, c, kOutside).size();
    }
  // What is left empty is enclosed by data: a hole.
  lid_.assign(n, NAN);
  for (size_t c = 0; c < n; ++c) {
    if (state[c] != kEmpty) continue;
    const std::vector<size_t> cells_of = flood(grid_, state, c, kHole);
    Hole h;
    h.cells = cells_of.size();
    h.area = double(h.cells) * grid_.cell() * grid_.cell();
    h.lid_z = rim_height(grid_, cells_of);
    for (size_t k : cells_of) {
      lid_[k] = h.lid_z;
      const double x = grid_.x0() + double(k % size_t(grid_.nx())) * grid_.cell();
      const double y = grid_.y0() + double(k / size_t(grid_.nx())) * grid_.cell();
      h.box.add(Vec3(x, y, h.lid_z));
      h.box.add(Vec3(x + grid_.cell(), y + grid_.cell(), h.lid_z));
    }
    holes_.push_back(h);
  }
  if (holes_.empty()) lid_.clear();
}

bool HoleMap::disc_touches_hole(double x, double y, double r) const {
  if (holes_.empty()) return false;
  const int c0 = grid_.col(x - r), c1 = grid_.col(x + r), r0 = grid_.row(y - r), r1 = grid_.row(y + r);
  for (int row = r0; row <= r1; ++row)
    for (int col = c0; col <= c1; ++col)
      if (!std::isnan(lid_[grid_.index(col, row)]) && grid_.distance2(col, row, x, y) <= r * r) return true;
  return false;
}

}  // namespace rosmill::core
