#include "rosmill/cloud/cloud_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "rosmill/error.hpp"

namespace rosmill {
namespace {

// The cutter's profile, prepared once per query.
struct Profile {
  double R, r, Rf, R2, Rf2;
  explicit Profile(const Cutter& c) {
    R = c.radius();
    r = c.type == CutterType::FlatEnd ? 0.0 : c.type == CutterType::BallEnd ? R : std::clamp(c.corner_radius, 0.0, R);
    Rf = R - r;
    R2 = R * R;
    Rf2 = Rf * Rf;
  }
  // Tip height at which the cutter touches something at height z, plan distance² d2 (d2 <= R2).
  double tip(double z, double d2) const {
    if (d2 <= Rf2) return z;
    if (Rf == 0.0) return z - r + std::sqrt(std::max(0.0, r * r - d2));
    const double u = std::sqrt(d2) - Rf;
    return z - r + std::sqrt(std::max(0.0, r * r - u * u));
  }
};

}  // namespace

CloudSurface::CloudSurface(const PointCloud& cloud, const CloudSurfaceOptions& options) { build(cloud.points, options); }

CloudSurface::CloudSurface(const std::vector<Vec3>& points, const CloudSurfaceOptions& options) { build(points, options); }

void CloudSurface::build(const std::vector<Vec3>& points, const CloudSurfaceOptions& options) {
  if (points.empty()) throw Error("cloud surface", "the cloud has no points");
  for (const Vec3& p : points)
    if (!p.allFinite()) throw Error("cloud surface", "the cloud holds a NaN or infinite point (prepare it first)");
  Box3 box;
  for (const Vec3& p : points) box.add(p);
  const Vec3 size = box.size();
  const double cell = options.cell > 0 ? options.cell : auto_grid_cell(points.size(), std::max(size.x() * size.y(), 1e-6));
  grid_ = CloudGrid(points, cell);
  spacing_ = rosmill::mean_spacing(grid_);
  if (options.detect_holes && spacing_ > 0) {
    const double hole_cell = options.hole_cell > 0 ? options.hole_cell : auto_hole_cell(grid_);
    holes_ = HoleMap(points, hole_cell);
  }
}

Drop CloudSurface::drop(const Cutter& cutter, double x, double y) const {
  const Profile pf(cutter);
  double best = -std::numeric_limits<double>::infinity();
  const int c0 = grid_.col(x - pf.R), c1 = grid_.col(x + pf.R);
  const int r0 = grid_.row(y - pf.R), r1 = grid_.row(y + pf.R);
  for (int row = r0; row <= r1; ++row)
    for (int col = c0; col <= c1; ++col) {
      const size_t cell = grid_.index(col, row);
      // Every candidate is at most its point's z: a cell whose highest point is not above the best so far
      // cannot raise the cutter.
      if (grid_.zmax(cell) <= best) continue;
      for (const GridPoint* p = grid_.begin(cell), *e = grid_.end(cell); p != e; ++p) {
        if (p->z <= best) continue;
        const double dx = p->x - x, dy = p->y - y, d2 = dx * dx + dy * dy;
        if (d2 > pf.R2) continue;
        best = std::max(best, pf.tip(p->z, d2));
      }
    }
  if (holes_.any()) {
    // A lid is a flat rectangle: the cutter touches it at the rectangle's nearest point.
    const CloudGrid& hg = holes_.grid();
    const double cs = hg.cell();
    const int h0 = hg.col(x - pf.R), h1 = hg.col(x + pf.R), v0 = hg.row(y - pf.R), v1 = hg.row(y + pf.R);
    for (int row = v0; row <= v1; ++row)
      for (int col = h0; col <= h1; ++col) {
        const double lid = holes_.lid(hg.index(col, row));
        if (!(lid > best)) continue;
        const double lx = hg.x0() + col * cs, ly = hg.y0() + row * cs;
        const double dx = std::max({lx - x, 0.0, x - (lx + cs)});
        const double dy = std::max({ly - y, 0.0, y - (ly + cs)});
        const double d2 = dx * dx + dy * dy;
        if (d2 <= pf.R2) best = std::max(best, pf.tip(lid, d2));
      }
  }
  if (best == -std::numeric_limits<double>::infinity()) return Drop{grid_.bounds().min.z(), false};
  return Drop{best, true};
}

void CloudSurface::drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 512), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i != range.end(); ++i) out[i] = drop(cutter, xy[i].x(), xy[i].y());
  });
}

}  // namespace rosmill
