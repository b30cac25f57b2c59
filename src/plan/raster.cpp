#include "rosmill/plan/raster.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "rosmill/plan/step_error.hpp"

namespace rosmill::core {

namespace {

// A link may stay down only when it keeps the axis inside the region and the footprint off skipped ground
// (checked every `step`).
bool link_allowed(const Surface& surface, const Region& region, double reach, const Vec2& a, const Vec2& b,
                  double step) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
  for (int k = 1; k < n; ++k) {
    const Vec2 p = a + (b - a) * (double(k) / n);
    if (!region.empty() && !inside_region(region, p)) return false;
    if (surface.skips(p.x(), p.y(), reach)) return false;
  }
  return true;
}

// The stretches of a piece where the surface does not skip the footprint, probed every `step`; a stretch runs
// between two probes that are not skipped. Counts the probes left out.
std::vector<std::pair<Vec2, Vec2>> unskipped(const Surface& surface, const std::pair<Vec2, Vec2>& piece,
                                             double reach, double step, size_t& skipped) {
  const Vec2 a = piece.first, b = piece.second;
  const size_t n = std::max<size_t>(1, size_t(std::ceil((b - a).norm() / step)));
  std::vector<std::pair<Vec2, Vec2>> out;
  bool open = false;
  Vec2 first, last;
  for (size_t k = 0; k <= n; ++k) {
    const Vec2 p = a + (b - a) * (double(k) / double(n));
    const bool skip = surface.skips(p.x(), p.y(), reach);
    skipped += skip;
    if (!skip) {
      if (!open) first = p;
      last = p, open = true;
    }
    if (open && (skip || k == n)) {
      if (last != first) out.emplace_back(first, last);
      open = false;
    }
  }
  return out;
}

// One sampled line: its stretches' CL points, and what the sampling did.
struct SampledLine {
  std::vector<std::vector<Vec3>> stretches;
  StepErrorCounts counts;
  size_t skipped = 0;
};

}  // namespace

Job raster_on(const Surface& surface, const PlanParams& params, const RasterOptions& options,
              const PlanProgress& progress) {
  const PlanFrame f = make_frame(surface, params);
  const double reach = f.cutter.radius() + f.allowance;
  const Vec2 lo = f.part.min.head<2>() - Vec2::Constant(reach), hi = f.part.max.head<2>() + Vec2::Constant(reach);
  const bool step_error = params.sampling == Sampling::StepError;
  const double step = step_error ? step_error_spacing(f) : std::min(0.25 * f.cutter.radius(), 1.0);
  // At most the diagonal's count of lines, each at most the diagonal long; a chord costs its end and three
  // checks (sample_segment), a probe of the footprint one more.
  const double n_lines = step_count((hi - lo).norm(), f.stepover), n_samples = step_count((hi - lo).norm(), step);
  check_plan_work("raster", {n_lines * n_samples * (step_error ? 1 : 5), n_lines * n_samples,
                             count_text(n_lines, "lines") + " x " + count_text(n_samples, "samples")}, f);
  const std::vector<ScanLine> lines = scan_lines(lo, hi, params.angle_deg, f.stepover, options.boundary);
  // One stretch a-b sampled by the plan's policy into CL points.
  auto sample = [&](const Vec2& a, const Vec2& b, std::vector<Vec3>& pts, StepErrorCounts& counts) {
    if (step_error)
      sample_step_error(surface, f, a, b, pts, counts);
    else
      sample_segment(surface, f, a, b, step, pts);
    drop_collinear(pts);
  };

  // Sample every piece of every line on both cores.
  std::vector<SampledLine> cl(lines.size());
  parallel_blocks(lines.size(), progress, 0.0, 0.9, [&](size_t i) {
    for (const auto& piece : lines[i].pieces)
      for (const auto& stretch : unskipped(surface, piece, reach, step, cl[i].skipped)) {
        std::vector<Vec3> pts;
        sample(stretch.first, stretch.second, pts, cl[i].counts);
        cl[i].stretches.push_back(std::move(pts));
      }
  });

  Toolpath tp;
  tp.strategy = "raster";
  tp.tool = params.tool;
  MoveWriter w(tp, f);
  w.begin_pass("raster " + std::to_string(params.angle_deg) + " deg");
  StepErrorCounts links;
  bool reverse = false;
  for (SampledLine& sampled : cl) {
    auto& line = sampled.stretches;
    if (line.empty()) continue;
    if (reverse) {
      std::reverse(line.begin(), line.end());
      for (auto& pts : line) std::reverse(pts.begin(), pts.end());
    }
    for (const auto& pts : line) {
      const Vec3& start = pts.front();
      const double gap = (start.head<2>() - w.position().head<2>()).norm();
      if (!w.at_safe() && options.zigzag && gap <= 1.5 * f.stepover + 1e-9 &&
          link_allowed(surface, options.boundary, reach, w.position().head<2>(), start.head<2>(), step)) {
        // Zigzag link along the surface to the next line's start.
        std::vector<Vec3> link;
        sample(w.position().head<2>(), start.head<2>(), link, links);
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
  if (options.report) {
    PlanReport& r = *options.report;
    r = PlanReport{};
    r.strategy = tp.strategy;
    r.lines = lines.size();
    r.sample_step = step;
    r.cl_points = tp.move_count();
    for (const SampledLine& l : cl) {
      r.samples += l.counts.samples;
      r.buffer_points += l.counts.buffers;
      r.checked_points += l.counts.checked;
      r.skipped_samples += l.skipped;
    }
    r.samples += links.samples, r.buffer_points += links.buffers, r.checked_points += links.checked;
  }
  return {tp};
}

}  // namespace rosmill::core
