#include "rosmill/verify/multi_axis.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/geometry/mesh_ray.hpp"
#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/surface_samples.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/stock/material_along.hpp"

namespace rosmill::core::verify {
namespace {

constexpr double kUnreachedMm = 1.0;  // no tool came this near: unreached, not merely left

// One sample's reading.
struct Reading {
  double rest = 0, gouge = 0;
};

struct Sums {
  double area = 0, rest_area = 0, max_rest = 0, above = 0, unreached = 0, gouged = 0, gouge = 0;
  size_t deepest = SIZE_MAX, most = SIZE_MAX;
};

}  // namespace

MultiAxisVerifyResult verify_multi_axis(const Mesh& design, const stock::MultiAxisProgram& program,
                                        const StockSpec& stock_spec, const VerifyOptions& options, double stepover) {
  const auto start = std::chrono::steady_clock::now();
  if (design.face_count() == 0) throw Error("design", "has no facets");
  MultiAxisVerifyResult r;
  r.moves = program.moves.size();
  stock::InProcessStock stock = in_process_stock(design, stock_spec, options);
  r.removal = stock.remove(program);
  const double tolerance = options.compare.tolerance;
  // A ball's scallop on a flat at the stepover (deviation.hpp), with the finishing (last) tool.
  r.limit_mm = tolerance +
               (stepover > 0 && !program.tools.empty() ? scallop_theory(program.tools.back().cutter, stepover) : 0.0);
  const SurfaceSamples samples = sample_surface(design, std::max(0.5 * options.resolution, sample_spacing(design)));
  r.samples = samples.size();
  const MeshRays rays(design);
  const double step = std::max(0.05, 0.5 * options.resolution);
  std::vector<Reading> readings(samples.size());
  PerThread<std::optional<stock::StockProbe>> probes;
  for_each_piece<size_t>(0, samples.size(), 256, [&](size_t b, size_t e) {
    std::optional<stock::StockProbe>& probe = probes.local();
    if (!probe) probe.emplace(stock, 0.25);
    for (size_t k = b; k < e; ++k) {
      const Vec3& p = samples.points[k];
      const Vec3 n = samples.normals[k].normalized();
      readings[k].rest = stock::material_thickness(*probe, stock, rays, p, n, r.limit_mm, step);
      readings[k].gouge = stock::gouge_under(*probe, p, n, tolerance, step);
    }
  });
  Sums s;
  const stock::MultiAxisSweep& sweep = stock.multi_axis_sweep();
  for (size_t k = 0; k < samples.size(); ++k) {
    const double w = samples.weights[k];
    const Reading& g = readings[k];
    s.area += w;
    s.rest_area += w * g.rest;
    if (g.rest > s.max_rest) s.max_rest = g.rest, s.most = k;
    if (g.rest > r.limit_mm) {
      s.above += w;
      if (sweep.depth(samples.points[k]) < -kUnreachedMm) s.unreached += w;
    }
    if (g.gouge > 0) {
      s.gouged += w;
      if (g.gouge > s.gouge) s.gouge = g.gouge, s.deepest = k;
    }
  }
  r.area_mm2 = s.area;
  r.max_rest_mm = s.max_rest;
  r.mean_rest_mm = s.area > 0 ? s.rest_area / s.area : 0;
  if (s.most != SIZE_MAX) r.max_rest_at = samples.points[s.most];
  r.above_area_mm2 = s.above;
  r.unreached_area_mm2 = s.unreached;
  r.gouged_area_mm2 = s.gouged;
  if (s.deepest != SIZE_MAX) {
    r.max_gouge_mm = s.gouge;
    r.gouge_at = samples.points[s.deepest];
    uint32_t move = 0;
    const Vec3 n = samples.normals[s.deepest].normalized();
    if (sweep.depth(r.gouge_at - 0.5 * s.gouge * n, &move) > -INFINITY && move < program.moves.size())
      r.gouge_source = program.moves[move].source;
  }
  r.stock_mm3 = stock.volume();
  r.left_mm3 = r.stock_mm3 - report(design).volume;
  r.rest.resize(readings.size());
  r.gouge.resize(readings.size());
  for (size_t k = 0; k < readings.size(); ++k)
    r.rest[k] = float(readings[k].rest), r.gouge[k] = float(readings[k].gouge);
  r.surface = samples;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace rosmill::core::verify
