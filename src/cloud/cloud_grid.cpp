#include "rosmill/cloud/cloud_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"

namespace rosmill::core {

CloudGrid::CloudGrid(const std::vector<Vec3>& points, double cell, size_t max_cells) {
  if (!(cell > 0) || !std::isfinite(cell)) throw Error("cloud grid", "cell size must be a positive number");
  for (const Vec3& p : points) bounds_.add(p);
  if (points.empty()) {
    nx_ = ny_ = 1;
    start_.assign(2, 0);
    zmax_.assign(1, -std::numeric_limits<double>::infinity());
    return;
  }
  if (points.size() >= std::numeric_limits<uint32_t>::max()) throw Error("cloud grid", "too many points");
  x0_ = bounds_.min.x();
  y0_ = bounds_.min.y();
  const double w = bounds_.max.x() - x0_, h = bounds_.max.y() - y0_;
  // Grow the cell until the grid fits the cap (a few stray far points must not exhaust memory).
  for (;;) {
    const double cx = std::floor(w / cell) + 1, cy = std::floor(h / cell) + 1;
    if (cx * cy <= double(max_cells)) {
      nx_ = int(cx);
      ny_ = int(cy);
      break;
    }
    cell *= 1.5;
  }
  cell_ = cell;
  const size_t ncell = size_t(nx_) * size_t(ny_);

  // Counting sort into cells: two passes, no per-cell vectors.
  std::vector<uint32_t> cell_of(points.size());
  start_.assign(ncell + 1, 0);
  for (size_t i = 0; i < points.size(); ++i) {
    cell_of[i] = uint32_t(index(col(points[i].x()), row(points[i].y())));
    ++start_[cell_of[i] + 1];
  }
  for (size_t c = 0; c < ncell; ++c) start_[c + 1] += start_[c];
  std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
  points_.resize(points.size());
  zmax_.assign(ncell, -std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    const uint32_t c = cell_of[i];
    points_[fill[c]++] = GridPoint{p.x(), p.y(), p.z()};
    zmax_[c] = std::max(zmax_[c], p.z());
  }
}

CloudGrid CloudGrid::regridded(double cell) const {
  std::vector<Vec3> pts;
  pts.reserve(points_.size());
  for (const GridPoint& p : points_) pts.emplace_back(p.x, p.y, p.z);
  return CloudGrid(pts, cell);
}

double auto_grid_cell(size_t n, double xy_area) {
  if (n == 0 || !(xy_area > 0)) return 1.0;
  // About four points per cell on a uniformly covered footprint.
  return std::max(1e-3, std::sqrt(4.0 * xy_area / double(n)));
}

namespace {

// Squared distance from (x, y, z) to the nearest point other than itself (3-D), or in plan view when `plan`:
// scan rings of cells outward until the ring's inner distance exceeds the best distance found.
double nearest_distance2(const CloudGrid& g, double x, double y, double z, bool plan) {
  const int c0 = g.col(x), r0 = g.row(y);
  double best2 = std::numeric_limits<double>::infinity();
  const int max_ring = std::max(g.nx(), g.ny());
  for (int ring = 0; ring <= max_ring; ++ring) {
    const double inner = (ring - 1) * g.cell();
    if (ring > 0 && inner > 0 && inner * inner > best2) break;
    for (int r = r0 - ring; r <= r0 + ring; ++r) {
      if (r < 0 || r >= g.ny()) continue;
      const bool edge_row = (r == r0 - ring || r == r0 + ring);
      for (int c = c0 - ring; c <= c0 + ring; c += (edge_row ? 1 : 2 * ring)) {
        if (c >= 0 && c < g.nx()) {
          const size_t cell = g.index(c, r);
          for (const GridPoint* p = g.begin(cell); p != g.end(cell); ++p) {
            const double dx = p->x - x, dy = p->y - y, dz = plan ? 0.0 : p->z - z;
            const double d2 = dx * dx + dy * dy + dz * dz;
            if (d2 > 0 && d2 < best2) best2 = d2;
          }
        }
        if (ring == 0) break;
      }
    }
  }
  return best2;
}

double nearest_distance(const CloudGrid& g, const GridPoint& q) {
  const double d2 = nearest_distance2(g, q.x, q.y, q.z, false);
  return std::isfinite(d2) ? std::sqrt(d2) : 0.0;
}

// Radical inverse in base b (a Halton sequence coordinate): evenly spread probe positions, no random state.
double radical_inverse(size_t i, size_t b) {
  double f = 1.0, r = 0.0;
  for (; i > 0; i /= b) {
    f /= double(b);
    r += f * double(i % b);
  }
  return r;
}

}  // namespace

double mean_spacing(const CloudGrid& grid, size_t samples) {
  const size_t n = grid.size();
  if (n < 2) return 0.0;
  const size_t m = std::min(n, samples);
  const double stride = double(n) / double(m);
  const double sum = reduce_pieces(
      size_t(0), m, size_t(256), 0.0,
      [&](size_t begin, size_t end, double acc) {
        for (size_t k = begin; k != end; ++k) acc += nearest_distance(grid, grid.points()[size_t(double(k) * stride)]);
        return acc;
      },
      [](double a, double b) { return a + b; });
  return sum / double(m);
}

double spacing_quantile(const CloudGrid& grid, double q, size_t samples) {
  const size_t n = grid.size();
  if (n < 2) return 0.0;
  const size_t m = std::min(n, samples);
  const double stride = double(n) / double(m);
  std::vector<double> d(m);
  for_each_piece<size_t>(0, m, 256, [&](size_t begin, size_t end) {
    for (size_t k = begin; k != end; ++k) d[k] = nearest_distance(grid, grid.points()[size_t(double(k) * stride)]);
  });
  const size_t at = std::min(m - 1, size_t(std::clamp(q, 0.0, 1.0) * double(m - 1)));
  std::nth_element(d.begin(), d.begin() + at, d.end());
  return d[at];
}

double sampling_radius(const CloudGrid& grid, const CloudGrid& coarse, double q, size_t samples) {
  std::vector<size_t> inside;
  for (int r = 1; r + 1 < coarse.ny(); ++r)
    for (int c = 1; c + 1 < coarse.nx(); ++c) {
      bool full = true;
      for (int dr = -1; dr <= 1 && full; ++dr)
        for (int dc = -1; dc <= 1 && full; ++dc) full = coarse.count(coarse.index(c + dc, r + dr)) > 0;
      if (full) inside.push_back(coarse.index(c, r));
    }
  if (inside.empty() || grid.size() < 2) return 0.0;
  const size_t m = std::max<size_t>(samples, 1);
  std::vector<double> d(m);
  for_each_piece<size_t>(0, m, 256, [&](size_t begin, size_t end) {
    for (size_t k = begin; k != end; ++k) {
      const size_t cell = inside[k % inside.size()];
      const double x = coarse.x0() + (double(cell % size_t(coarse.nx())) + radical_inverse(k + 1, 2)) * coarse.cell();
      const double y = coarse.y0() + (double(cell / size_t(coarse.nx())) + radical_inverse(k + 1, 3)) * coarse.cell();
      d[k] = std::sqrt(nearest_distance2(grid, x, y, 0.0, true));
    }
  });
  const size_t at = std::min(m - 1, size_t(std::clamp(q, 0.0, 1.0) * double(m - 1)));
  std::nth_element(d.begin(), d.begin() + at, d.end());
  return d[at];
}

}  // namespace rosmill::core
