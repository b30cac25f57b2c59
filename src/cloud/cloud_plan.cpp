#include "rosmill/cloud/cloud_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <tbb/parallel_for.h>

#include "cloud_route.hpp"
#include "rosmill/cloud/cloud_interpolation.hpp"
#include "rosmill/error.hpp"

namespace rosmill {

using cloud_detail::ProgressRange;
using cloud_detail::Route;
using cloud_detail::Zigzag;

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

void check_stage(const CloudStage& s, const std::string& w) {
  if (!(s.tool.cutter.diameter > 0) || !std::isfinite(s.tool.cutter.diameter))
    throw Error(w, "tool diameter must be a positive number");
  if (!(s.allowance >= 0) || !std::isfinite(s.allowance)) throw Error(w, "allowance must be >= 0");
  if (!(s.stepover >= 0) || !std::isfinite(s.stepover)) throw Error(w, "stepover must be >= 0");
}

void check_options(const CloudPlanOptions& o, const std::string& w) {
  if (!(o.tolerance > 0) || !std::isfinite(o.tolerance)) throw Error(w, "tolerance must be a positive number");
  if (!(o.safe_clearance > 0) || !std::isfinite(o.safe_clearance)) throw Error(w, "safe clearance must be positive");
  if (!std::isfinite(o.angle_deg)) throw Error(w, "raster angle must be a number of degrees");
}

// Emits a retract to safe_z from the current position (a known-free vertical move out of the cut).
void retract(ToolpathPass& pass, const Vec3& at, double safe_z) {
  if (at.z() < safe_z) pass.moves.push_back(Move{Vec3(at.x(), at.y(), safe_z), MoveType::Rapid, 0.0});
}

// Rapid at safe_z (the clearance height) to above `to`, then down at feed: rapids stay at or above the clearance
// height (issue 7's rule, checked by the machine limits), so the descent to `free_z` (known free: material a
// previous level removed) goes at the cutting feed and the rest, into the material, at the plunge feed.
void approach(ToolpathPass& pass, const Vec3& to, double safe_z, double free_z, const Tool& tool) {
  pass.moves.push_back(Move{Vec3(to.x(), to.y(), safe_z), MoveType::Rapid, 0.0});
  if (free_z < safe_z && free_z > to.z()) pass.moves.push_back(Move{Vec3(to.x(), to.y(), free_z), MoveType::Feed, tool.feed});
  pass.moves.push_back(Move{to, MoveType::Plunge, tool.plunge_feed});
}

// A cutting move: a vertical descent goes in at the plunge feed, anything else at the cutting feed.
void cut_to(ToolpathPass& pass, const Vec3& from, const Vec3& to, const Tool& tool) {
  const bool down = from.head<2>() == to.head<2>() && to.z() < from.z();
  pass.moves.push_back(Move{to, down ? MoveType::Plunge : MoveType::Feed, down ? tool.plunge_feed : tool.feed});
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

// HolePolicy::Skip: the samples whose footprint (radius r) reaches a hole.
std::vector<bool> blocked_samples(const CloudSurface& s, const std::vector<Vec2>& xy, double r, HolePolicy policy) {
  std::vector<bool> blocked(xy.size(), false);
  if (policy != HolePolicy::Skip || !s.holes().any()) return blocked;
  for (size_t i = 0; i < xy.size(); ++i) blocked[i] = s.holes().disc_touches_hole(xy[i].x(), xy[i].y(), r);
  return blocked;
}

// A plan of more drop-cutter queries than this is refused with the cloud's size (a cloud read in the wrong units
// would otherwise run for hours): at about a million queries a second it is minutes of work.
constexpr double kMaxSamples = 2e8;

void check_size(const std::string& strategy, double samples, const Box3& box) {
  if (samples <= kMaxSamples) return;
  char text[256];
  std::snprintf(text, sizeof text,
                "would need about %.3g drop-cutter queries (more than %.0g) over a cloud of %.0f x %.0f mm: check the "
                "cloud's units, or raise the stepover or the tolerance",
                samples, kMaxSamples, box.size().x(), box.size().y());
  throw Error(strategy, text);
}

double corner_of(const Cutter& c) {
  return c.type == CutterType::FlatEnd ? 0.0 : c.type == CutterType::BallEnd ? c.radius() : c.corner_radius;
}

// Rough: between two samples h apart the cutter moves level at the higher of their heights T (a staircase: up
// first or down last). A point at plan distance e from that move is at most sqrt(e² + h²/4) from the nearer
// sample. T is the drop of a probe whose flat part (radius Rf, the cutter's R - r) is grown by `side`: its
// height above the tip at distance d is the cutter's at max(0, d - side), which is at most the cutter's at e as
// soon as sqrt(e² + h²/4) - side <= max(e, Rf) for every e, i.e. side >= sqrt(Rf² + h²/4) - Rf. The probe also
// carries the allowance δ. So no point comes closer than δ to a level move. kRoughSlack keeps a margin.
constexpr double kRoughSlack = 1.1;

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
  check_stage(o.rough, "cloud-rough");
  check_options(o, "cloud-rough");
  if (!(o.depth_of_cut > 0) || !std::isfinite(o.depth_of_cut)) throw Error("cloud-rough", "depth of cut must be positive");
  const ProgressRange prog(progress, 0.0, 1.0);
  const double R = o.rough.tool.cutter.radius(), delta = o.rough.allowance;
  const double grid = o.rough.stepover > 0 ? o.rough.stepover : 2 * R - 0.5 * delta;
  if (!(grid > 0)) throw Error("cloud-rough", "grid size 2R - 0.5 allowance is not positive");
  const Box3 box = s.bounds();
  // Rows from y_min + 0.5δ every grid size until the cutter has covered y_max.
  std::vector<double> rows;
  for (double y = box.min.y() + 0.5 * delta;; y += grid) {
    rows.push_back(y);
    if (y + R >= box.max.y()) break;
  }
  // Samples h apart along the lines; the probe's flat part grown by `side` so that the footprints of two
  // neighbouring samples cover the band the cutter sweeps between them (see kRoughSlack).
  const double step = R / 4, flat = R - corner_of(o.rough.tool.cutter);
  const double side = kRoughSlack * (std::sqrt(flat * flat + step * step / 4) - flat);
  // Each level walks every sample (a few operations each, a tenth of a drop's cost).
  const double samples = (box.size().x() + 2 * (R + delta)) / step * double(rows.size());
  check_size("cloud-rough", samples * (1 + std::ceil(box.size().z() / o.depth_of_cut) / 10), box);
  const Route route =
      cloud_detail::whole_route(Zigzag(0.0, box.min.x() - R - delta, box.max.x() + R + delta, rows, step));
  const Cutter probe = Cutter::bull(2 * (R + delta + side), corner_of(o.rough.tool.cutter) + delta);
  std::vector<double> T = cloud_detail::route_drops(s, probe, route, prog.sub(0.0, 0.8));
  for (double& t : T) t += delta;
  const std::vector<bool> blocked = blocked_samples(s, route.xy, R + delta + side, o.holes);
  const size_t skipped = size_t(std::count(blocked.begin(), blocked.end(), true));

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
      for (size_t k = 1; k < pts.size(); ++k) cut_to(pass, pts[k - 1], pts[k], o.rough.tool);
      retract(pass, pts.back(), tp.safe_z);
      i = j + 1;
    }
    if (!pass.moves.empty()) tp.passes.push_back(std::move(pass));
    z_prev = z;
  }
  prog(1.0);
  if (report) {
    *report = CloudStageReport{};
    report->strategy = "cloud-rough";
    report->lines = route.lines;
    report->levels = levels;
    report->samples = T.size();
    report->cl_points = tp.move_count();
    report->skipped_samples = skipped;
    report->sample_step = step;
  }
  return tp;
}

namespace {

// One stretch of cutting along one raster line: CL points of the line's samples first..last (local indices).
struct Run {
  size_t first = 0, last = 0;
  std::vector<Vec3> pts;
};

struct LinePlan {
  std::vector<Run> runs;
  size_t samples = 0, buffers = 0, checked = 0, skipped = 0;
  size_t last_sample = 0;  // local index of the line's last sample
};

// A ball stage's line j: drops at the samples, the seed's buffer points, every move checked against the points.
LinePlan plan_line(const CloudSurface& s, const Zigzag& zz, size_t j, const Cutter& grown, double delta, double R,
                   const CloudPlanOptions& o) {
  LinePlan lp;
  std::vector<Vec2> xy;
  std::vector<uint8_t> corner;
  zz.samples(j, xy, corner);
  const size_t n = xy.size();
  lp.samples = j > 0 ? n - 1 : n;
  lp.last_sample = n - 1;
  std::vector<Drop> drops(n);
  s.drop_many(grown, xy.data(), n, drops.data());
  std::vector<Vec3> cl(n);
  // Never below the floor (the cloud's lowest point: the table the scan stands on). A ball that touches the
  // last points of the cloud with its side would otherwise hang its tip below them, beyond the part.
  const double floor_z = s.bounds().min.z();
  for (size_t i = 0; i < n; ++i) cl[i] = Vec3(xy[i].x(), xy[i].y(), std::max(drops[i].z, floor_z) + delta);
  const std::vector<bool> blocked = blocked_samples(s, xy, R + delta, o.holes);
  for (size_t i = j > 0 ? 1 : 0; i < n; ++i) lp.skipped += blocked[i];
  std::vector<uint32_t> kept;
  for (size_t i = 0; i < n;) {
    if (blocked[i]) {
      ++i;
      continue;
    }
    size_t k = i;
    while (k + 1 < n && !blocked[k + 1]) ++k;
    Run run;
    run.first = i;
    run.last = k;
    kept.clear();
    lp.buffers += buffer_points(cl, corner, i, k, 2 * R, 0.5 * o.tolerance, kept);
    run.pts.push_back(cl[kept[0]]);
    for (size_t m = 1; m < kept.size(); ++m)
      lp.checked += cloud_detail::checked_move(s, grown, delta, o.tolerance, cl[kept[m - 1]], cl[kept[m]], run.pts);
    lp.runs.push_back(std::move(run));
    i = k + 1;
  }
  return lp;
}

}  // namespace

Toolpath plan_cloud_raster(const CloudSurface& s, const CloudStage& stage, const std::string& strategy,
                           const CloudPlanOptions& o, const PlanProgress& progress, CloudStageReport* report) {
  check_stage(stage, strategy);
  check_options(o, strategy);
  if (!(stage.stepover > 0)) throw Error(strategy, "stepover must be positive");
  const ProgressRange prog(progress, 0.0, 1.0);
  const double R = stage.tool.cutter.radius(), delta = stage.allowance, reach = R + delta;
  double u0, u1, v0, v1;
  cloud_detail::box_extent(s.bounds(), o.angle_deg, u0, u1, v0, v1);
  const double nv_real = std::ceil((v1 - v0) / stage.stepover - 1e-9);
  // Fine sampling for the seed's step error: between samples h apart a ball's CL over level ground sags by
  // h²/(8R) = t/2. (Steeper or sharper CL curves are caught by the check of every move.)
  const double step = std::clamp(std::sqrt(4 * R * o.tolerance), 0.01, 0.5 * R);
  check_size(strategy, (nv_real + 1) * (u1 - u0 + 2 * reach + (v1 - v0) / std::max(nv_real, 1.0)) / step, s.bounds());
  const size_t nv = std::max<size_t>(1, size_t(nv_real));
  std::vector<double> rows;
  for (size_t j = 0; j <= nv; ++j) rows.push_back(v0 + (v1 - v0) * double(j) / double(nv));
  const Zigzag zz(o.angle_deg, u0 - reach, u1 + reach, rows, step);
  const Cutter grown = offset_cutter(stage.tool.cutter, delta);

  // Lines on both cores, in blocks (progress and cancellation between blocks).
  std::vector<LinePlan> lines(zz.lines());
  const size_t block = std::max<size_t>(1, lines.size() / 40);
  for (size_t b = 0; b < lines.size(); b += block) {
    const size_t e = std::min(lines.size(), b + block);
    tbb::parallel_for(b, e, [&](size_t j) { lines[j] = plan_line(s, zz, j, grown, delta, R, o); });
    prog(0.95 * double(e) / double(lines.size()));
  }

  // Assembly: one pass per line; a cut goes on from one line to the next through the step across, and stops
  // (retract) where the Skip policy leaves samples out.
  Toolpath tp = empty_toolpath(strategy, stage.tool, s, o.safe_clearance);
  CloudStageReport r;
  bool cutting = false;
  for (size_t j = 0; j < lines.size(); ++j) {
    LinePlan& lp = lines[j];
    ToolpathPass pass;
    pass.name = "line " + std::to_string(j + 1);
    for (Run& run : lp.runs) {
      const bool goes_on = cutting && j > 0 && run.first == 0;
      if (!goes_on) approach(pass, run.pts.front(), tp.safe_z, tp.safe_z, stage.tool);
      for (size_t k = 1; k < run.pts.size(); ++k) cut_to(pass, run.pts[k - 1], run.pts[k], stage.tool);
      cutting = true;
      if (run.last < lp.last_sample || j + 1 == lines.size()) {
        retract(pass, run.pts.back(), tp.safe_z);
        cutting = false;
      }
    }
    if (!pass.moves.empty()) tp.passes.push_back(std::move(pass));
    r.samples += lp.samples;
    r.buffer_points += lp.buffers;
    r.checked_points += lp.checked;
    r.skipped_samples += lp.skipped;
  }
  prog(1.0);
  if (report) {
    r.strategy = strategy;
    r.lines = zz.lines();
    r.cl_points = tp.move_count();
    r.sample_step = step;
    *report = r;
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

CloudSurfaceOptions cloud_surface_options(const CloudPlanOptions& o, double hole_cell) {
  CloudSurfaceOptions so;
  so.hole_cell = hole_cell;
  so.sampling_radius = o.sampling_radius;
  so.max_sink = o.tolerance;
  return so;
}

CloudJob plan_cloud_job(const std::vector<Vec3>& raw, const CloudPrepOptions& prep, const CloudPlanOptions& options,
                        const PlanProgress& progress) {
  const ProgressRange prog(progress, 0.0, 1.0);
  CloudJob out;
  prog(0.0);
  out.cloud = prepare_cloud(raw, prep, &out.prep);
  const CloudSurface surface(out.cloud, cloud_surface_options(options, out.prep.hole_cell));
  out.holes = surface.holes().holes();
  out.sampling_radius = surface.sampling_radius();
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

double positive_or(double value, double fallback, const char* name) {
  if (std::isnan(value)) return fallback;
  if (!(value > 0) || !std::isfinite(value)) throw Error(std::string("parameter ") + name, "must be a positive number");
  return value;
}

}  // namespace

CloudPlanOptions cloud_options_from_params(const PlanParams& p, const std::string& stage, HolePolicy holes) {
  CloudPlanOptions o;
  if (!(p.allowance >= 0) || !std::isfinite(p.allowance)) throw Error("parameter allowance", "must be >= 0");
  if (!(p.safe_clearance > 0) || !std::isfinite(p.safe_clearance))
    throw Error("parameter safe_clearance", "must be a positive number");
  if (!std::isfinite(p.angle_deg)) throw Error("parameter angle", "must be a number of degrees");
  o.tolerance = positive_or(p.tolerance, o.tolerance, "tolerance");
  o.angle_deg = p.angle_deg;
  o.safe_clearance = p.safe_clearance;
  o.holes = holes;
  o.finish.allowance = p.allowance;
  o.semi.allowance = p.allowance + 0.2;
  o.rough.allowance = p.allowance + 0.5;
  CloudStage* single = stage == "rough" ? &o.rough : stage == "semi" ? &o.semi : stage == "finish" ? &o.finish : nullptr;
  if (!single && stage != "all") throw Error("cloud plan", "unknown stage '" + stage + "' (rough, semi, finish, all)");
  const bool own_tool = single && !default_tool(p.tool);
  if (own_tool) {
    single->tool = p.tool;
    // A ball stage takes the tool's stepover; the rough keeps the seed's grid 2R - 0.5δ, which follows the tool.
    if (single != &o.rough) single->stepover = p.tool.stepover;
  }
  if (single) single->stepover = positive_or(p.stepover, single->stepover, "stepover");
  o.depth_of_cut = positive_or(p.stepdown, own_tool && single == &o.rough ? p.tool.stepdown : o.depth_of_cut, "stepdown");
  return o;
}

Job plan_cloud_strategy(const std::string& name, const PointCloud& cloud, const PlanParams& params, HolePolicy holes,
                        const PlanProgress& progress) {
  const std::string stage = name.rfind("cloud-", 0) == 0 ? name.substr(6) : name;
  const CloudPlanOptions o = cloud_options_from_params(params, stage, holes);
  if (cloud.points.empty()) throw Error(name, "needs a non-empty point cloud");
  const CloudSurface s(cloud, cloud_surface_options(o, 0.0));
  if (stage == "rough") return {plan_cloud_rough(s, o, progress)};
  if (stage == "semi") return {plan_cloud_raster(s, o.semi, "cloud-semi", o, progress)};
  if (stage == "finish") return {plan_cloud_raster(s, o.finish, "cloud-finish", o, progress)};
  return plan_cloud_all(s, o, progress);
}

Job cloud_rough_strategy(const PlanInput& in, const PlanParams& p, const PlanProgress& progress) {
  return plan_cloud_strategy("cloud-rough", cloud_of(in, "cloud-rough"), p, HolePolicy::Bridge, progress);
}

Job cloud_semi_strategy(const PlanInput& in, const PlanParams& p, const PlanProgress& progress) {
  return plan_cloud_strategy("cloud-semi", cloud_of(in, "cloud-semi"), p, HolePolicy::Bridge, progress);
}

Job cloud_finish_strategy(const PlanInput& in, const PlanParams& p, const PlanProgress& progress) {
  return plan_cloud_strategy("cloud-finish", cloud_of(in, "cloud-finish"), p, HolePolicy::Bridge, progress);
}

Job cloud_all_strategy(const PlanInput& in, const PlanParams& p, const PlanProgress& progress) {
  return plan_cloud_strategy("cloud-all", cloud_of(in, "cloud-all"), p, HolePolicy::Bridge, progress);
}

}  // namespace rosmill
