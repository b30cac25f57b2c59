#include "rosmill/plan/raster.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace rosmill {

void drop_collinear(std::vector<Vec3>& pts) {
  if (pts.size() < 3) return;
  size_t w = 1;
  for (size_t i = 1; i + 1 < pts.size(); ++i) {
    const Vec3& a = pts[w - 1];
    const Vec3& b = pts[i];
    const Vec3& c = pts[i + 1];
    const Vec3 ac = c - a;
    const double len2 = ac.squaredNorm();
    const bool on_line = len2 > 0 && (b - a).cross(ac).squaredNorm() / len2 < 1e-18 && (b - a).dot(ac) >= 0 &&
                         (b - a).dot(ac) <= len2;
    if (!on_line) pts[w++] = b;
  }
  pts[w++] = pts.back();
  pts.resize(w);
}

namespace {

// A link may stay down only when it keeps the axis inside the region (checked every `step`).
bool link_inside(const Region& region, const Vec2& a, const Vec2& b, double step) {
  if (region.empty()) return true;
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
  for (int k = 1; k < n; ++k)
    if (!inside_region(region, a + (b - a) * (double(k) / n))) return false;
  return true;
}

}  // namespace

Job raster_on(const Surface& surface, const PlanParams& params, const RasterOptions& options,
              const PlanProgress& progress) {
  const PlanFrame f = make_frame(surface, params);
  const double reach = f.cutter.radius() + f.allowance;
  const Vec2 lo = f.part.min.head<2>() - Vec2::Constant(reach), hi = f.part.max.head<2>() + Vec2::Constant(reach);
  const std::vector<ScanLine> lines = scan_lines(lo, hi, params.angle_deg, f.stepover, options.boundary);
  const double step = std::min(0.25 * f.cutter.radius(), 1.0);

  // Sample every piece of every line on both cores.
  std::vector<std::vector<std::vector<Vec3>>> cl(lines.size());
  parallel_blocks(lines.size(), progress, 0.0, 0.9, [&](size_t i) {
    for (const auto& piece : lines[i].pieces) {
      std::vector<Vec3> pts;
      sample_segment(surface, f, piece.first, piece.second, step, pts);
      drop_collinear(pts);
      cl[i].push_back(std::move(pts));
    }
  });

  Toolpath tp;
  tp.strategy = "raster";
  tp.tool = params.tool;
  MoveWriter w(tp, f);
  w.begin_pass("raster " + std::to_string(params.angle_deg) + " deg");
  bool reverse = false;
  for (auto& line : cl) {
    if (line.empty()) continue;
    if (reverse) {
      std::reverse(line.begin(), line.end());
      for (auto& pts : line) std::reverse(pts.begin(), pts.end());
    }
    for (const auto& pts : line) {
      const Vec3& start = pts.front();
      const double gap = (start.head<2>() - w.position().head<2>()).norm();
      if (!w.at_safe() && options.zigzag && gap <= 1.5 * f.stepover + 1e-9 &&
          link_inside(options.boundary, w.position().head<2>(), start.head<2>(), step)) {
        // Zigzag link along the surface to the next line's start.
        std::vector<Vec3> link;
        sample_segment(surface, f, w.position().head<2>(), start.head<2>(), step, link);
        drop_collinear(link);
        for (const Vec3& p : link) w.feed(p);
      } else {
        w.enter(start);
      }
      for (const Vec3& p : pts) w.feed(p);
    }
    if (options.zigzag) reverse = !reverse;
    else w.retract();
  }
  w.retract();
  check_cancel(progress, 1.0);
  return {tp};
}

Job raster_strategy(const Surface& surface, const PlanParams& params, const PlanProgress& progress) {
  return raster_on(surface, params, RasterOptions{}, progress);
}

}  // namespace rosmill
