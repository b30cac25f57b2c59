#include "rosmill/cloud/cloud_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "rosmill/cloud/cloud_sweep.hpp"
#include "rosmill/cutter/contact.hpp"
#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"

namespace rosmill::core {
namespace {

constexpr double kNothing = -std::numeric_limits<double>::infinity();

// The index cell, in auto_grid_cell()'s (about four points): 1.5 of them (about nine points) halves the cells a
// ball's footprint visits and costs little pruning (bench_cloud: finish about a quarter less CPU on relief-300k).
// The drop is the highest point under the footprint whatever the cell, so the size changes no result.
constexpr double kQueryCellScale = 1.5;

double corner_radius(const Cutter& c) {
  const double R = c.radius();
  return c.type == CutterType::FlatEnd ? 0.0 : c.type == CutterType::BallEnd ? R : std::clamp(c.corner_radius, 0.0, R);
}


}  // namespace

CloudSurface::CloudSurface(const PointCloud& cloud, const CloudSurfaceOptions& options) {
  build(cloud.points, options);
}

CloudSurface::CloudSurface(const std::vector<Vec3>& points, const CloudSurfaceOptions& options) {
  build(points, options);
}

void CloudSurface::build(const std::vector<Vec3>& points, const CloudSurfaceOptions& options) {
  if (points.empty()) throw Error("cloud surface", "the cloud has no points");
  if (!(options.max_sink > 0) || !std::isfinite(options.max_sink))
    throw Error("cloud surface", "the sink allowed between points must be a positive number of mm");
  if (!std::isnan(options.sampling_radius) && !(options.sampling_radius >= 0 && std::isfinite(options.sampling_radius)))
    throw Error("cloud surface", "the sampling radius must be >= 0 mm (or NaN: estimated)");
  for (const Vec3& p : points)
    if (!p.allFinite()) throw Error("cloud surface", "the cloud holds a NaN or infinite point (prepare it first)");
  Box3 box;
  for (const Vec3& p : points) box.add(p);
  const Vec3 size = box.size();
  const double cell = options.cell > 0
                          ? options.cell
                          : kQueryCellScale * auto_grid_cell(points.size(), std::max(size.x() * size.y(), 1e-6));
  grid_ = CloudGrid(points, cell);
  spacing_ = rosmill::core::mean_spacing(grid_);
  max_sink_ = options.max_sink;
  hole_policy_ = options.holes;
  const double hole_cell = options.hole_cell > 0 ? options.hole_cell : auto_hole_cell(grid_);
  if (options.detect_holes && spacing_ > 0) holes_ = HoleMap(points, hole_cell);
  if (!std::isnan(options.sampling_radius)) {
    sampling_radius_ = options.sampling_radius;
  } else if (spacing_ > 0) {
    sampling_radius_ =
        rosmill::core::sampling_radius(grid_, options.detect_holes ? holes_.grid() : CloudGrid(points, hole_cell));
  }
}

SweepHit CloudSurface::sweep(const Cutter& cutter, const Vec3& a, const Vec3& b, double floor) const {
  return sweep_depth(*this, cutter, a, b, floor);
}

bool CloudSurface::skips(double x, double y, double radius) const {
  return hole_policy_ == HolePolicy::Skip && holes_.any() && holes_.disc_touches_hole(x, y, radius);
}

double CloudSurface::support_radius(const Cutter& cutter) const {
  return std::max(0.0, sampling_radius_ - std::sqrt(2.0 * corner_radius(cutter) * max_sink_));
}

Cutter CloudSurface::supported(const Cutter& cutter) const {
  const double c = support_radius(cutter);
  if (c == 0.0) return cutter;
  return Cutter::bull(cutter.diameter + 2 * c, corner_radius(cutter));
}

Drop CloudSurface::drop(const Cutter& cutter, double x, double y) const {
  const GridPoint* hint = nullptr;
  return drop_hinted(CutterProfile(supported(cutter)), CutterProfile(cutter), x, y, hint);
}

Drop CloudSurface::drop_hinted(const CutterProfile& cp, const CutterProfile& lid_cp, double x, double y,
                               const GridPoint*& hint) const {
  double best = kNothing;
  const GridPoint* winner = nullptr;
  // A good first bound lets most cells be skipped: the point that held the cutter at the previous position
  // along the route usually holds it nearly as high here.
  if (hint) {
    const double dx = hint->x - x, dy = hint->y - y, d2 = dx * dx + dy * dy;
    if (d2 <= cp.R2) best = hint->z - cp.height_sq(d2), winner = hint;
  }
  auto scan = [&](int col, int row, double d2min) {
    const size_t cell = grid_.index(col, row);
    // zmax alone first (empty cells, cells below the best): saves the ball's square root.
    if (grid_.zmax(cell) <= best || grid_.zmax(cell) - cp.height_sq(d2min) <= best) return;
    for (const GridPoint *p = grid_.begin(cell), *e = grid_.end(cell); p != e; ++p) {
      if (p->z <= best) continue;
      const double dx = p->x - x, dy = p->y - y, d2 = dx * dx + dy * dy;
      if (d2 > cp.R2) continue;
      const double z = p->z - cp.height_sq(d2);
      if (z > best) best = z, winner = p;
    }
  };
  // Then the cell under the axis: its points usually hold the cutter highest.
  const int cc = grid_.col(x), cr = grid_.row(y);
  scan(cc, cr, 0.0);
  const int c0 = grid_.col(x - cp.R), c1 = grid_.col(x + cp.R);
  const int r0 = grid_.row(y - cp.R), r1 = grid_.row(y + cp.R);
  for (int row = r0; row <= r1; ++row)
    for (int col = c0; col <= c1; ++col) {
      const double d2 = grid_.distance2(col, row, x, y);
      if ((col == cc && row == cr) || d2 > cp.R2) continue;
      scan(col, row, d2);
    }
  hint = winner;
  if (holes_.any()) {
    // A lid is a flat rectangle (a surface, not a point: no support disc): the cutter touches it at the
    // rectangle's nearest point.
    const CloudGrid& hg = holes_.grid();
    const int h0 = hg.col(x - lid_cp.R), h1 = hg.col(x + lid_cp.R);
    const int v0 = hg.row(y - lid_cp.R), v1 = hg.row(y + lid_cp.R);
    for (int row = v0; row <= v1; ++row)
      for (int col = h0; col <= h1; ++col) {
        const double lid = holes_.lid(hg.index(col, row));
        if (!(lid > best)) continue;
        const double d2 = hg.distance2(col, row, x, y);
        if (d2 <= lid_cp.R2) best = std::max(best, lid - lid_cp.height_sq(d2));
      }
  }
  if (best == kNothing) return Drop{grid_.bounds().min.z(), false};
  return Drop{best, true};
}

void CloudSurface::drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const {
  const CutterProfile cp(supported(cutter)), lid_cp(cutter);
  for_each_piece<size_t>(0, n, 512, [&](size_t begin, size_t end) {
    const GridPoint* hint = nullptr;
    for (size_t i = begin; i != end; ++i) out[i] = drop_hinted(cp, lid_cp, xy[i].x(), xy[i].y(), hint);
  });
}

}  // namespace rosmill::core
