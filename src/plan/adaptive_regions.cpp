#include "adaptive_regions.hpp"

#include <cmath>

#include "rosmill/slice/slicer.hpp"

namespace rosmill::core {
namespace {

constexpr double kAbove = 1e-6;  // a cell stands above a level when higher by more than this

// The cells of a height grid standing above z, as the union of their rows' runs.
clip::Paths cells_above(const MaterialTop& m, const std::vector<float>& heights, double z) {
  clip::Paths runs;
  for (int j = 0; j < m.ny; ++j)
    for (int i = 0; i < m.nx;) {
      if (!(heights[size_t(j) * m.nx + i] > z + kAbove)) {
        ++i;
        continue;
      }
      const int i0 = i;
      while (i < m.nx && heights[size_t(j) * m.nx + i] > z + kAbove) ++i;
      const clip::Paths run = clip::rectangle(Vec2(m.x0 + i0 * m.cell, m.y0 + j * m.cell),
                                              Vec2(m.x0 + i * m.cell, m.y0 + (j + 1) * m.cell));
      runs.push_back(run.front());
    }
  return clip::unite(runs, {});
}

clip::Paths material_above(const PlanParams& params, const PlanFrame& f, double z) {
  if (params.material) return cells_above(*params.material, params.material->top, z);
  if (params.stock_mesh) {
    clip::Paths loops;
    for (const Contour& c : slice_mesh(*params.stock_mesh, {z}).front().contours)
      if (c.closed && c.points.size() >= 3) loops.push_back(clip::to_path(c.points));
    return clip::even_odd(loops);
  }
  if (z >= f.stock.max.z()) return {};
  return clip::rectangle(f.stock.min.head<2>(), f.stock.max.head<2>());
}

// Where the cutter would go into the part at the level: the even-odd fill of the waterline's loops, grown by the
// loops' own tolerance (their chords may cut a corner of the true contour by that much) and by `simplify`, the
// most its boundary then moves when its vertices are thinned (fewer vertices: faster offsets of every ring).
clip::Paths part_blocked(const std::vector<Loop>& loops, double grow, double simplify, double arc_tolerance) {
  clip::Paths paths;
  for (const Loop& loop : loops) {
    clip::Path p;
    for (const Vec3& v : loop) p.push_back(clip::to_point(v.head<2>()));
    paths.push_back(std::move(p));
  }
  return clip::simplify(clip::offset(clip::even_odd(paths), grow + simplify, arc_tolerance), simplify);
}

}  // namespace

LevelRegions level_regions(const PlanParams& params, const PlanFrame& f, double z, const std::vector<Loop>& loops,
                           const Vec2& work_lo, const Vec2& work_hi, double arc_tolerance, double skin) {
  const double R = f.cutter.radius();
  clip::Paths blocked = part_blocked(loops, f.tolerance, 0.5 * arc_tolerance, arc_tolerance);
  // The fixture keeps the tool the link clearance away: the flutes from what stands above the level, the shank
  // from what stands above the flutes, the holder from what stands above the stick-out.
  if (params.material && !params.material->fixture.empty()) {
    const Tool& t = params.tool;
    const double bands[3][2] = {{0.0, R},
                                {t.cutter.flute_length, std::max(R, 0.5 * t.cutter.shank_diameter)},
                                {t.stick_out_mm(), std::max(R, 0.5 * t.holder_mm())}};
    for (const auto& band : bands)
      blocked = clip::unite(blocked, clip::offset(cells_above(*params.material, params.material->fixture, z + band[0]),
                                                  band[1] + params.link_clearance, arc_tolerance));
  }
  LevelRegions r;
  r.allowed = clip::subtract(clip::rectangle(work_lo, work_hi), blocked);
  r.material = material_above(params, f, z);
  // Within a hair less than R of the allowed centres: the ring that runs along a wall rounds off its corners by
  // the arc tolerance, and the thin skin it leaves at the wall (the wall's own material, not a cut) must not count
  // as material that makes the whole ring a cut.
  r.target = clip::intersect(r.material, clip::offset(r.allowed, R - skin, arc_tolerance));
  return r;
}

}  // namespace rosmill::core
