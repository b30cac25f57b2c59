#include "rosmill/plan/grid_rough.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rosmill/error.hpp"

namespace rosmill::core {
namespace {

double corner_of(const Cutter& c) {
  return c.type == CutterType::FlatEnd ? 0.0 : c.type == CutterType::BallEnd ? c.radius() : c.corner_radius;
}

// Between two samples h apart the cutter moves level at the higher of their heights T (a staircase). A point at
// plan distance e from that move is at most sqrt(e² + h²/4) from the nearer sample. T is the drop of a probe
// whose flat part (radius Rf, the cutter's R - r) is grown by `side`: its height above the tip at distance d is
// the cutter's at max(0, d - side), which is at most the cutter's at e as soon as sqrt(e² + h²/4) - side <=
// max(e, Rf) for every e, i.e. side >= sqrt(Rf² + h²/4) - Rf. kSlack keeps a margin.
constexpr double kSlack = 1.1;

// The zigzag as one run of samples at most `step` apart: each line of `lines` (one piece each), odd lines
// backwards, joined by the step across from one line's end to the next one's start.
std::vector<Vec2> zigzag_route(const std::vector<ScanLine>& lines, double step) {
  std::vector<Vec2> route;
  // By value: `a` may be route.back(), which push_back moves (AddressSanitizer found the reference read after it).
  auto walk = [&](const Vec2 a, const Vec2 b) {
    const size_t n = std::max<size_t>(1, size_t(std::ceil((b - a).norm() / step)));
    for (size_t i = route.empty() ? 0 : 1; i <= n; ++i) route.push_back(a + (b - a) * (double(i) / double(n)));
  };
  for (size_t j = 0; j < lines.size(); ++j) {
    if (lines[j].pieces.empty()) continue;
    Vec2 a = lines[j].pieces.front().first, b = lines[j].pieces.front().second;
    if (j % 2) std::swap(a, b);
    if (!route.empty()) walk(route.back(), a);
    walk(a, b);
  }
  return route;
}

// The drops at every sample (both cores), in chunks, reporting progress over [0, to].
std::vector<double> route_drops(const Surface& s, const Cutter& probe, const std::vector<Vec2>& route,
                                const PlanProgress& progress, double to) {
  std::vector<double> z(route.size());
  std::vector<Drop> drops;
  const size_t chunk = 65536;
  drops.resize(std::min(route.size(), chunk));
  for (size_t i = 0; i < route.size(); i += chunk) {
    const size_t m = std::min(chunk, route.size() - i);
    s.drop_many(probe, route.data() + i, m, drops.data());
    for (size_t k = 0; k < m; ++k) z[i + k] = drops[k].z;
    check_cancel(progress, to * double(i + m) / double(route.size()));
  }
  return z;
}

}  // namespace

Job grid_rough_on(const Surface& s, const PlanParams& params, const PlanProgress& progress, PlanReport* report) {
  // The paper's stock is the part's box: levels from its top, the safe height the clearance above it.
  PlanParams box_stock = params;
  box_stock.stock_margin = 0.0;
  const PlanFrame f = make_frame(s, box_stock);
  const double R = f.cutter.radius(), delta = f.allowance;
  const double grid = std::isnan(params.stepover) ? 2 * R - 0.5 * delta : f.stepover;
  if (!(grid > 0)) throw Error("grid-rough", "grid size 2R - 0.5 allowance is not positive");
  const Box3& box = f.part;
  // Rows from y_min + 0.5δ every grid size until the cutter has covered y_max.
  const double step = R / 4, flat = R - corner_of(f.cutter);
  // Each level walks every sample (a few operations each, a tenth of a drop's cost).
  const double samples = step_count(box.size().x() + 2 * (R + delta), step) * step_count(box.size().y(), grid);
  const double n_levels = step_count(box.size().z(), f.stepdown);
  check_plan_work("grid-rough", {samples * (1 + n_levels / 10), samples,
                                 count_text(samples, "samples") + " x " + count_text(n_levels, "levels")}, f);
  size_t rows = 1;
  while (box.min.y() + 0.5 * delta + double(rows - 1) * grid + R < box.max.y()) ++rows;
  const double y0 = box.min.y() + 0.5 * delta, y1 = y0 + double(rows - 1) * grid;
  const double x0 = box.min.x() - R - delta, x1 = box.max.x() + R + delta;
  const double side = kSlack * (std::sqrt(flat * flat + step * step / 4) - flat);
  std::vector<ScanLine> lines = scan_lines(Vec2(x0, y0), Vec2(x1, y1), 0.0, grid, {});
  lines.resize(std::min(lines.size(), rows));  // one row: scan_lines gives the same line twice
  const std::vector<Vec2> route = zigzag_route(lines, step);
  const Cutter probe = Cutter::bull(2 * (R + delta + side), corner_of(f.cutter) + delta);
  std::vector<double> T = route_drops(s, probe, route, progress, 0.8);
  for (double& t : T) t = std::max(t, box.min.z()) + delta;
  std::vector<uint8_t> blocked(route.size());
  for (size_t i = 0; i < route.size(); ++i) blocked[i] = s.skips(route[i].x(), route[i].y(), R + delta + side);

  Toolpath tp;
  tp.strategy = "grid-rough";
  tp.tool = params.tool;
  MoveWriter w(tp, f);
  const double top = box.max.z(), floor_z = box.min.z() + delta;
  // Short idle stretches are crossed in the cut rather than by retract, rapid and plunge.
  const size_t bridge = size_t(std::ceil(2 * R / step));
  size_t levels = 0;
  for (double z_prev = top; z_prev > floor_z + 1e-9; ++levels) {
    const double z = std::max(z_prev - f.stepdown, floor_z);
    bool opened = false;
    // Active: this level removes material there (the previous level stayed above max(z, T)).
    std::vector<uint8_t> active(T.size());
    for (size_t i = 0; i < T.size(); ++i) active[i] = !blocked[i] && T[i] < z_prev - 1e-9;
    for (size_t i = 0; i < T.size();) {
      if (!active[i]) {
        ++i;
        continue;
      }
      // A span of active samples, idle gaps up to `bridge` samples (not blocked ones) included.
      size_t j = i;
      for (size_t k = i + 1; k < T.size(); ++k) {
        if (blocked[k]) break;
        if (active[k]) j = k;
        else if (k - j > bridge) break;
      }
      std::vector<Vec3> pts;
      auto cl = [&](size_t k) { return std::max(z, T[k]); };
      pts.push_back(Vec3(route[i].x(), route[i].y(), cl(i)));
      for (size_t k = i; k < j; ++k) {
        const double za = cl(k), zb = cl(k + 1);
        const Vec2& a = route[k];
        const Vec2& b = route[k + 1];
        if (zb > za) pts.push_back(Vec3(a.x(), a.y(), zb));  // up first
        pts.push_back(Vec3(b.x(), b.y(), std::max(za, zb)));
        if (zb < za) pts.push_back(Vec3(b.x(), b.y(), zb));  // down last
      }
      drop_collinear(pts);
      if (!opened) {
        char name[64];
        std::snprintf(name, sizeof name, "level %zu z=%.3f", levels + 1, z);
        w.begin_pass(name);
        opened = true;
      }
      w.enter(pts.front(), levels == 0 ? NAN : z_prev + 1.0);
      for (size_t k = 1; k < pts.size(); ++k) w.cut_to(pts[k]);
      w.retract();
      i = j + 1;
    }
    z_prev = z;
  }
  check_cancel(progress, 1.0);
  if (report) {
    *report = PlanReport{};
    report->strategy = tp.strategy;
    report->lines = rows;
    report->levels = levels;
    report->samples = T.size();
    report->cl_points = tp.move_count();
    report->skipped_samples = size_t(std::count(blocked.begin(), blocked.end(), 1));
    report->sample_step = step;
  }
  return {tp};
}

}  // namespace rosmill::core
