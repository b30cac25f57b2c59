#include "rosmill/cloud/cloud_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cloud_route.hpp"
#include "rosmill/error.hpp"

namespace rosmill {

using cloud_detail::ProgressRange;
using cloud_detail::Route;

namespace {

Tool seed_tool(int id, const char* name, const Cutter& c, double feed, double plunge, double rpm) {
  Tool t;
  t.id = id;
  t.name = name;
  t.cutter = c;
  t.feed = feed;
  t.plunge_feed = plunge;
  t.spindle_rpm = rpm;
  t.stepover = c.type == CutterType::FlatEnd ? c.diameter : 0.5 * c.diameter;
  t.stepdown = c.type == CutterType::FlatEnd ? 2.0 : 0.5 * c.radius();
  return t;
}

void check_stage(const CloudStage& s, const char* name) {
  const std::string w = std::string("cloud ") + name;
  if (!(s.tool.cutter.diameter > 0)) throw Error(w, "tool diameter must be positive");
  if (!(s.allowance >= 0)) throw Error(w, "allowance must be >= 0");
  if (!(s.stepover >= 0)) throw Error(w, "stepover must be >= 0");
}

// Emits a retract to safe_z from the current position (a known-free vertical move out of the cut).
void retract(ToolpathPass& pass, const Vec3& at, double safe_z) {
  if (at.z() < safe_z) pass.moves.push_back(Move{Vec3(at.x(), at.y(), safe_z), MoveType::Rapid, 0.0});
}

// Rapid at safe_z to above `to`, rapid down to `free_z` (known free), plunge to `to`.
void approach(ToolpathPass& pass, const Vec3& to, double safe_z, double free_z, const Tool& tool) {
  pass.moves.push_back(Move{Vec3(to.x(), to.y(), safe_z), MoveType::Rapid, 0.0});
  if (free_z < safe_z && free_z > to.z()) pass.moves.push_back(Move{Vec3(to.x(), to.y(), free_z), MoveType::Rapid, 0.0});
  pass.moves.push_back(Move{to, MoveType::Plunge, tool.plunge_feed});
}

Toolpath empty_toolpath(const std::string& strategy, const Tool& tool, const CloudSurface& s, double clearance) {
  Toolpath tp;
  tp.strategy = strategy;
  tp.tool = tool;
  tp.safe_z = s.bounds().max.z() + clearance;
  tp.clearance_z = tp.safe_z;
  tp.start = Vec3(s.bounds().min.x(), s.bounds().min.y(), tp.safe_z);
  return tp;
}

std::vector<bool> blocked_samples(const CloudSurface& s, const Route& route, double r, HolePolicy policy, size_t* count) {
  std::vector<bool> blocked(route.xy.size(), false);
  if (policy != HolePolicy::Skip || !s.holes().any()) return blocked;
  for (size_t i = 0; i < route.xy.size(); ++i) {
    blocked[i] = s.holes().disc_touches_hole(route.xy[i].x(), route.xy[i].y(), r);
    if (blocked[i] && count) ++*count;
  }
  return blocked;
}

// Rough: the straight move between two samples h apart at the higher of their heights sweeps a band of
// half-width R. Computing T with the flat part of the cutter grown by kRoughSide, the two samples' footprints
// cover that band whenever h <= 2 sqrt(2 R kRoughSide), so no point in the band is above the move.
constexpr double kRoughSide = 0.05;  // mm of extra radial clearance in roughing

}  // namespace

CloudPlanOptions::CloudPlanOptions() {
  rough.tool = seed_tool(1, "flat 10 mm (rough)", Cutter::flat(10.0), 1200.0, 300.0, 8000.0);
  rough.stepover = 0.0;  // the seed's grid 2R - 0.5δ
  rough.allowance = 0.5;
  semi.tool = seed_tool(2, "ball 5 mm (semi-finish)", Cutter::ball(5.0), 1500.0, 400.0, 12000.0);
  semi.stepover = 2.0;
  semi.allowance = 0.2;
  finish.tool = seed_tool(3, "ball 3 mm (finish)", Cutter::ball(3.0), 1800.0, 400.0, 16000.0);
  finish.stepover = 0.3;
  finish.allowance = 0.0;
}

Toolpath plan_cloud_rough(const CloudSurface& s, const CloudPlanOptions& o, const PlanProgress& progress,
                          CloudStageReport* report) {
  check_stage(o.rough, "rough");
  if (!(o.depth_of_cut > 0)) throw Error("cloud rough", "depth of cut must be positive");
  const ProgressRange prog(progress, 0.0, 1.0);
  const double R = o.rough.tool.cutter.radius(), delta = o.rough.allowance;
  const double grid = o.rough.stepover > 0 ? o.rough.stepover : 2 * R - 0.5 * delta;
  if (!(grid > 0)) throw Error("cloud rough", "grid size 2R - 0.5 allowance is not positive");
  const Box3 box = s.bounds();
  // Rows from y_min + 0.5δ every grid size until the cutter has covered y_max.
  std::vector<double> rows;
  for (double y = box.min.y() + 0.5 * delta;; y += grid) {
    rows.push_back(y);
    if (y + R >= box.max.y()) break;
  }
  const double step = std::min(R / 4, 0.9 * 2 * std::sqrt(2 * R * kRoughSide));
  const Route route = cloud_detail::zigzag_route(0.0, box.min.x() - R - delta, box.max.x() + R + delta, rows, step);
  Cutter probe = offset_cutter(o.rough.tool.cutter, delta);
  if (probe.type == CutterType::FlatEnd) {
    probe.type = CutterType::BullNose;
    probe.corner_radius = 0.0;
  }
  probe.diameter += 2 * kRoughSide;  // grows the flat part, not the corner
  std::vector<double> T = cloud_detail::route_drops(s, probe, route, prog.sub(0.0, 0.8));
  for (double& t : T) t += delta;
  size_t skipped = 0;
  const std::vector<bool> blocked = blocked_samples(s, route, R + delta + kRoughSide, o.holes, &skipped);

  Toolpath tp = empty_toolpath("cloud-rough", o.rough.tool, s, o.safe_clearance);
  const double top = box.max.z(), floor_z = box.min.z() + delta;
  // Short idle stretches are crossed in the cut rather than by retract, rapid and plunge.
  const size_t bridge = size_t(std::ceil(2 * R / step));
  size_t levels = 0;
  for (double z_prev = top; z_prev > floor_z + 1e-9; ++levels) {
    const double z = std::max(z_prev - o.depth_of_cut, floor_z);
    ToolpathPass pass;
    char name[64];
    std::snprintf(name, sizeof name, "level %zu z=%.3f", levels + 1, z);
    pass.name = name;
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
      pts.push_back(Vec3(route.xy[i].x(), route.xy[i].y(), cl(i)));
      for (size_t k = i; k < j; ++k) {
        const double za = cl(k), zb = cl(k + 1);
        const Vec2& a = route.xy[k];
        const Vec2& b = route.xy[k + 1];
        if (zb > za) pts.push_back(Vec3(a.x(), a.y(), zb));  // up first
        pts.push_back(Vec3(b.x(), b.y(), std::max(za, zb)));
        if (zb < za) pts.push_back(Vec3(b.x(), b.y(), zb));  // down last
      }
      cloud_detail::drop_collinear(pts);
      approach(pass, pts.front(), tp.safe_z, levels == 0 ? tp.safe_z : z_prev + 1.0, o.rough.tool);
      for (size_t k = 1; k < pts.size(); ++k) pass.moves.push_back(Move{pts[k], MoveType::Feed, o.rough.tool.feed});
      retract(pass, pts.back(), tp.safe_z);
      i = j + 1;
    }
    if (!pass.moves.empty()) tp.passes.push_back(std::move(pass));
    z_prev = z;
    if (levels > 100000) throw Error("cloud rough", "too many levels");
  }
  prog(1.0);
  if (report) {
    *report = CloudStageReport{};
    report->strategy = "cloud-rough";
    report->lines = route.lines();
    report->levels = levels;
    report->samples = T.size();
    report->cl_points = tp.move_count();
    report->skipped_samples = skipped;
    report->sample_step = step;
  }
  return tp;
}

Toolpath plan_cloud_raster(const CloudSurface& s, const CloudStage& stage, const std::string& strategy,
                           const CloudPlanOptions& o, const PlanProgress& progress, CloudStageReport* report) {
  check_stage(stage, strategy.c_str());
  if (!(stage.stepover > 0)) throw Error(strategy, "stepover must be positive");
  if (!(o.tolerance > 0)) throw Error(strategy, "tolerance must be positive");
  const ProgressRange prog(progress, 0.0, 1.0);
  const double R = stage.tool.cutter.radius(), delta = stage.allowance, reach = R + delta;
  double u0, u1, v0, v1;
  cloud_detail::box_extent(s.bounds(), o.angle_deg, u0, u1, v0, v1);
  const size_t nv = std::max<size_t>(1, size_t(std::ceil((v1 - v0) / stage.stepover - 1e-9)));
  std::vector<double> rows;
  for (size_t j = 0; j <= nv; ++j) rows.push_back(v0 + (v1 - v0) * double(j) / double(nv));
  // Fine sampling: a ball's CL curve has radius >= R, so it sags at most h²/(8R) = t/2 between samples.
  const double step = std::clamp(std::sqrt(4 * R * o.tolerance), 0.01, 0.5 * R);
  const Route route = cloud_detail::zigzag_route(o.angle_deg, u0 - reach, u1 + reach, rows, step);
  const std::vector<double> z = cloud_detail::route_drops(s, offset_cutter(stage.tool.cutter, delta), route, prog.sub(0.0, 0.9));
  std::vector<Vec3> cl(z.size());
  for (size_t i = 0; i < z.size(); ++i) cl[i] = Vec3(route.xy[i].x(), route.xy[i].y(), z[i] + delta);
  size_t skipped = 0;
  const std::vector<bool> blocked = blocked_samples(s, route, reach, o.holes, &skipped);

  Toolpath tp = empty_toolpath(strategy, stage.tool, s, o.safe_clearance);
  size_t buffers = 0;
  std::vector<uint32_t> kept;
  size_t line = 0;
  ToolpathPass pass;
  bool cutting = false;
  auto next_line = [&](size_t i) {
    while (line < route.lines() && route.line_start[line] <= i) {
      if (!pass.moves.empty()) tp.passes.push_back(std::move(pass));
      pass = ToolpathPass{};
      pass.name = "line " + std::to_string(++line);
    }
  };
  for (size_t i = 0; i < cl.size();) {
    if (blocked[i]) {
      ++i;
      continue;
    }
    size_t j = i;
    while (j + 1 < cl.size() && !blocked[j + 1]) ++j;
    kept.clear();
    buffers += cloud_detail::buffer_points(cl, route.corner, i, j, 2 * R, 0.5 * o.tolerance, kept);
    for (size_t k = 0; k < kept.size(); ++k) {
      next_line(kept[k]);
      const Vec3& p = cl[kept[k]];
      if (!cutting) {
        approach(pass, p, tp.safe_z, tp.safe_z, stage.tool);
        cutting = true;
      } else {
        pass.moves.push_back(Move{p, MoveType::Feed, stage.tool.feed});
      }
    }
    retract(pass, cl[j], tp.safe_z);
    cutting = false;
    i = j + 1;
  }
  if (!pass.moves.empty()) tp.passes.push_back(std::move(pass));
  prog(1.0);
  if (report) {
    *report = CloudStageReport{};
    report->strategy = strategy;
    report->lines = route.lines();
    report->samples = cl.size();
    report->cl_points = tp.move_count();
    report->buffer_points = buffers;
    report->skipped_samples = skipped;
    report->sample_step = step;
  }
  return tp;
}

Job plan_cloud_all(const CloudSurface& s, const CloudPlanOptions& o, const PlanProgress& progress,
                   std::vector<CloudStageReport>* reports) {
  const ProgressRange prog(progress, 0.0, 1.0);
  CloudStageReport r[3];
  Job job;
  job.push_back(plan_cloud_rough(s, o, [&](double f) { prog.sub(0.0, 0.1)(f); return true; }, &r[0]));
  job.push_back(plan_cloud_raster(s, o.semi, "cloud-semi", o, [&](double f) { prog.sub(0.1, 0.3)(f); return true; }, &r[1]));
  job.push_back(plan_cloud_raster(s, o.finish, "cloud-finish", o, [&](double f) { prog.sub(0.3, 1.0)(f); return true; }, &r[2]));
  if (reports) reports->assign(r, r + 3);
  return job;
}

CloudJob plan_cloud_job(const std::vector<Vec3>& raw, const CloudPrepOptions& prep, const CloudPlanOptions& options,
                        const PlanProgress& progress) {
  const ProgressRange prog(progress, 0.0, 1.0);
  CloudJob out;
  prog(0.0);
  out.cloud = prepare_cloud(raw, prep, &out.prep);
  CloudSurfaceOptions so;
  so.hole_cell = prep.hole_cell;
  const CloudSurface surface(out.cloud, so);
  out.holes = surface.holes().holes();
  prog(0.05);
  out.job = plan_cloud_all(surface, options, [&](double f) { prog.sub(0.05, 1.0)(f); return true; }, &out.stages);
  return out;
}

// --- strategy table entries -------------------------------------------------------------------------------

namespace {

bool default_tool(const Tool& t) {
  const Cutter d;
  return t.name.empty() && t.cutter.type == d.type && t.cutter.diameter == d.diameter &&
         t.cutter.corner_radius == d.corner_radius;
}

const PointCloud& cloud_of(const PlanInput& input, const char* strategy) {
  if (!input.cloud || input.cloud->points.empty()) throw Error(strategy, "needs a non-empty point cloud");
  return *input.cloud;
}

}  // namespace

CloudPlanOptions cloud_options_from_params(const PlanParams& p, const std::string& stage) {
  CloudPlanOptions o;
  if (!(p.allowance >= 0)) throw Error("allowance", "must be >= 0");
  o.tolerance = p.tolerance > 0 ? p.tolerance : o.tolerance;
  o.angle_deg = p.angle_deg;
  o.safe_clearance = p.safe_clearance;
  o.finish.allowance = p.allowance;
  o.semi.allowance = p.allowance + 0.2;
  o.rough.allowance = p.allowance + 0.5;
  if (std::isfinite(p.stepdown)) o.depth_of_cut = p.stepdown;
  CloudStage* single = stage == "rough" ? &o.rough : stage == "semi" ? &o.semi : stage == "finish" ? &o.finish : nullptr;
  if (single) {
    if (std::isfinite(p.stepover)) single->stepover = p.stepover;
    if (!default_tool(p.tool)) single->tool = p.tool;
  }
  return o;
}

Job cloud_rough_strategy(const PlanInput& in, const PlanParams& p, const PlanProgress& progress) {
  const CloudSurface s(cloud_of(in, "cloud-rough"));
  return {plan_cloud_rough(s, cloud_options_from_params(p, "rough"), progress)};
}

Job cloud_semi_strategy(const PlanInput& in, const PlanParams& p, const PlanProgress& progress) {
  const CloudSurface s(cloud_of(in, "cloud-semi"));
  const CloudPlanOptions o = cloud_options_from_params(p, "semi");
  return {plan_cloud_raster(s, o.semi, "cloud-semi", o, progress)};
}

Job cloud_finish_strategy(const PlanInput& in, const PlanParams& p, const PlanProgress& progress) {
  const CloudSurface s(cloud_of(in, "cloud-finish"));
  const CloudPlanOptions o = cloud_options_from_params(p, "finish");
  return {plan_cloud_raster(s, o.finish, "cloud-finish", o, progress)};
}

Job cloud_all_strategy(const PlanInput& in, const PlanParams& p, const PlanProgress& progress) {
  const CloudSurface s(cloud_of(in, "cloud-all"));
  return plan_cloud_all(s, cloud_options_from_params(p, "all"), progress);
}

}  // namespace rosmill
