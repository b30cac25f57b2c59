#include "rosmill/plan/rough.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "rosmill/cutter/contact.hpp"
#include "rosmill/error.hpp"
#include "rosmill/plan/levels.hpp"
#include "rosmill/plan/stock.hpp"

#include "body_guard.hpp"

namespace rosmill::core {
namespace {

// One scan line sampled once: positions along it, the CL heights of the widened cutter and (with a job's
// material) the highest material under it.
struct SampledLine {
  Vec2 origin, dir;
  std::vector<double> s, h, material;
};

// Where the cutter at level z meets material of a job's map: unions of [s - half, s + half] over the samples with
// material above z under the widened cutter, gaps of air shorter than `air_gap` bridged (one feed through a short
// gap costs less than a retract and a re-entry), kept to the line's ends.
std::vector<std::pair<double, double>> material_spans(const SampledLine& line, double z, double half,
                                                      double air_gap) {
  std::vector<std::pair<double, double>> spans;
  for (size_t i = 0; i < line.s.size(); ++i) {
    if (!(line.material[i] > z + 1e-6)) continue;
    const double a = std::max(line.s[i] - half, line.s.front()), b = std::min(line.s[i] + half, line.s.back());
    if (!spans.empty() && a <= spans.back().second + air_gap) spans.back().second = b;
    else spans.emplace_back(a, b);
  }
  return spans;
}

// Free spans of a line at level z: unions of [s - half, s + half] over samples whose widened CL is <= z and where
// no body of the tool meets the material (`blocked`).
template <class Blocked>
std::vector<std::pair<double, double>> free_spans(const SampledLine& line, double z, double half,
                                                  const Blocked& blocked) {
  std::vector<std::pair<double, double>> spans;
  for (size_t i = 0; i < line.s.size(); ++i) {
    if (line.h[i] > z || blocked(line.origin + line.s[i] * line.dir)) continue;
    const double a = line.s[i] - half, b = line.s[i] + half;
    if (!spans.empty() && a <= spans.back().second + 1e-12) spans.back().second = b;
    else spans.emplace_back(a, b);
  }
  // Keep to the sampled stretch: the ends are the line's own ends.
  for (auto& sp : spans) sp.first = std::max(sp.first, line.s.front()), sp.second = std::min(sp.second, line.s.back());
  return spans;
}

// Ramps from (a, z_from) down to z along the piece a-b (back and forth), ending at a at height z.
void ramp_in(MoveWriter& w, const Vec2& a, const Vec2& b, double z_from, double z, double slope) {
  const double len = (b - a).norm();
  double zc = z_from;
  bool forward = true;
  if (len < 1e-6) {
    w.plunge_to(Vec3(a.x(), a.y(), z));
    return;
  }
  // Each leg descends at most slope * len; the last leg returns to a.
  while (zc > z + 1e-12) {
    const double drop = std::min(zc - z, slope * len);
    const double frac = drop / (slope * len);
    const Vec2 from = forward ? a : b;
    const Vec2 to = forward ? b : a;
    const Vec2 p = from + (to - from) * frac;
    zc -= drop;
    w.plunge_to(Vec3(p.x(), p.y(), zc));
    if (frac < 1.0) {  // stopped part way: go back to a at z
      w.feed(Vec3(a.x(), a.y(), z));
      return;
    }
    forward = !forward;
  }
  w.feed(Vec3(a.x(), a.y(), z));
}

}  // namespace

Job rough_on(const Surface& surface, const PlanParams& params, const RoughOptions& options,
             const PlanProgress& progress) {
  const PlanFrame f = make_frame(surface, params);
  if (!(options.ramp_slope > 0)) throw Error("rough", "ramp slope must be > 0");
  const double R = f.cutter.radius();
  const double spacing = std::min(0.25 * R, 0.5), half = 0.5 * spacing;
  // The widened cutter: radius + half the spacing, same corner (see rough.hpp).
  Cutter wide = f.drop_cutter;
  wide.diameter += 2 * half;
  if (wide.type == CutterType::BallEnd) wide.type = CutterType::BullNose;
  PlanFrame fw = f;
  fw.drop_cutter = wide;

  const Vec2 lo = f.stock.min.head<2>(), hi = f.stock.max.head<2>();
  // Every line sampled once, then walked at every level (about a tenth of a drop per sample and level).
  const double n_lines = step_count((hi - lo).norm(), f.stepover), n_samples = step_count((hi - lo).norm(), spacing);
  const double n_levels = step_count(f.stock.size().z(), f.stepdown);
  check_plan_work("rough", {n_lines * n_samples * (1 + n_levels / 10), n_lines * n_samples,
                            count_text(n_lines, "lines") + " x " + count_text(n_samples, "samples") + " x " +
                                count_text(n_levels, "levels")}, f);
  const std::vector<ScanLine> scan = scan_lines(lo, hi, params.angle_deg, f.stepover, {});
  std::vector<SampledLine> lines(scan.size());
  parallel_blocks(scan.size(), progress, 0.0, 0.8, [&](size_t i) {
    if (scan[i].pieces.empty()) return;
    const Vec2 a = scan[i].pieces.front().first, b = scan[i].pieces.front().second;
    SampledLine& L = lines[i];
    L.origin = a;
    const double len = (b - a).norm();
    L.dir = len > 0 ? Vec2((b - a) / len) : Vec2(1, 0);
    const int n = std::max(1, static_cast<int>(std::ceil(len / spacing)));
    for (int k = 0; k <= n; ++k) {
      const double s = len * k / n;
      const Vec2 p = a + s * L.dir;
      L.s.push_back(s);
      L.h.push_back(cl_height(surface, fw, p.x(), p.y()));
      if (params.material) L.material.push_back(params.material->highest_cut_under(p, R + half));
    }
  });

  // Levels from the stock top down every step-down and at every flat face plus the allowance (levels.hpp); the
  // last at the part's floor plus the allowance.
  const double floor = f.part.min.z() + f.allowance;
  const std::vector<double> levels = roughing_levels(f.stock.max.z(), floor, f.stepdown, flat_face_heights(surface, f));
  std::unique_ptr<StockReach> reach;
  if (params.stock_mesh && !params.material)
    reach = std::make_unique<StockReach>(*params.stock_mesh, levels, f.stock.max.z(), R, f.tolerance);
  const double air_gap = std::isnan(params.air_gap) ? 2 * R : params.air_gap;
  // A job's material, lowered as the levels cut it (only where a cut certainly took it): links pass over it.
  std::optional<MaterialTop> left;
  if (params.material) left = *params.material;
  const CutterProfile profile(f.cutter);
  auto cut_at_level = [&](const Vec2& from, const Vec2& to, double z) {
    if (left) left->lower_along(from, to, R, z, [&](double d) { return profile.height(d); });
  };
  // A straight link from `from` to `to` at a level stays in the stock's reach (always, for the box); over a
  // job's material it is at most the air gap long.
  auto link_in_reach = [&](size_t li, const Vec2& from, const Vec2& to) {
    if (left) return (to - from).norm() <= air_gap;
    if (!reach) return true;
    const double len = (to - from).norm();
    if (len < 1e-9) return true;
    const auto in = reach->along(li, from, (to - from) / len, len);
    return in.size() == 1 && in[0].first <= 1e-9 && in[0].second >= len - 1e-9;
  };

  Toolpath tp;
  tp.strategy = "rough";
  tp.tool = params.tool;
  MoveWriter w(tp, f);
  // Over a job's material a piece is reached by a rapid just over the material on the way (link_clearance above
  // it) instead of the safe height, checked along the whole link against what is left.
  // The rapid down stops the approach over the material under the cutter there (or over at_z).
  auto go_to = [&](const Vec2& a, double at_z) {
    const Vec2 from = w.position().head<2>();
    const double c = params.link_clearance;
    const double over = std::max(left->highest_along(from, a, R) + c, std::max(w.position().z(), at_z));
    const double under = left->clear_height(a, R, [&](double d) { return profile.height(d); });
    w.link_to(Vec3(a.x(), a.y(), at_z), over, std::max(under, at_z) + params.approach);
  };
  double above = f.stock.max.z();
  BodyGuard guard;
  for (size_t li = 0; li < levels.size(); ++li) {
    const double z = levels[li];
    bool reverse = false, begun = !left;  // over a job's material a level that meets none has no pass at all
    if (begun) w.begin_pass("level z " + std::to_string(z));
    if (left) guard.at_level(*left, params.tool, f.allowance, z);
    for (const SampledLine& L : lines) {
      if (L.s.empty()) continue;
      auto spans = free_spans(L, z, half, [&](const Vec2& p) { return guard.blocked(p); });
      std::vector<std::pair<double, double>> keep;
      if (reach) keep = reach->along(li, L.origin, L.dir, L.s.back());
      if (left) keep = material_spans(L, z, half, air_gap);
      if (reach || left) spans = intersect_spans(spans, keep);
      if (!spans.empty() && !begun) w.begin_pass("level z " + std::to_string(z)), begun = true;
      // A piece end where the line crosses the stock's reach: the cutter there is a radius clear of the slab's
      // material (and the slabs above were cleared or air), so it goes straight down, no ramp.
      auto in_air = [&](double s) {
        for (const auto& k : keep)
          if ((s == k.first && k.first > 0) || (s == k.second && k.second < L.s.back())) return true;
        return false;
      };
      if (reverse) {
        std::reverse(spans.begin(), spans.end());
        for (auto& sp : spans) std::swap(sp.first, sp.second);
      }
      for (auto sp : spans) {
        Vec2 a = L.origin + sp.first * L.dir, b = L.origin + sp.second * L.dir;
        if (!w.at_safe() && std::abs(w.position().z() - z) < 1e-12) {
          // Stay down when the straight link at this level is proven free (sampled like the lines).
          const Vec2 from = w.position().head<2>();
          const double len = (a - from).norm();
          bool free = len <= 2 * f.stepover && link_in_reach(li, from, a);
          const int n = std::max(1, static_cast<int>(std::ceil(len / spacing)));
          for (int k = 0; free && k <= n; ++k) {
            const Vec2 p = from + (a - from) * (double(k) / n);
            free = cl_height(surface, fw, p.x(), p.y()) <= z;
          }
          if (free) {
            w.feed(Vec3(a.x(), a.y(), z));
            w.feed(Vec3(b.x(), b.y(), z));
            cut_at_level(from, a, z);
            cut_at_level(a, b, z);
            continue;
          }
        }
        // A piece with one end in air is entered there, whatever the zigzag's direction.
        if (!in_air(sp.first) && in_air(sp.second)) std::swap(sp.first, sp.second), std::swap(a, b);
        if (in_air(sp.first)) {
          if (left) go_to(a, z);
          else w.enter(Vec3(a.x(), a.y(), z));
        } else {
          if (left) go_to(a, above);
          else w.enter(Vec3(a.x(), a.y(), above));
          ramp_in(w, a, b, above, z, options.ramp_slope);
        }
        w.feed(Vec3(b.x(), b.y(), z));
        cut_at_level(a, b, z);
      }
      reverse = !reverse;
    }
    if (!left) w.retract();
    above = z;
    check_cancel(progress, 0.8 + 0.2 * double(li + 1) / levels.size());
  }
  w.retract();
  return {tp};
}

Job rough_strategy(const Surface& surface, const PlanParams& params, const PlanProgress& progress) {
  return rough_on(surface, params, RoughOptions{}, progress);
}

}  // namespace rosmill::core
