#include "rosmill/plan/contour_toolpath.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/work_bound.hpp"

namespace rosmill::core {
namespace {

// Layer heights from the top down: Zmax - k * stepdown above Zmin, then Zmin itself.
std::vector<double> layer_heights(const Mesh& mesh, double stepdown) {
  std::vector<double> z;
  const double top = mesh.bbox.max.z(), bottom = mesh.bbox.min.z();
  for (size_t k = 1;; ++k) {
    const double h = top - double(k) * stepdown;
    if (h <= bottom + 1e-9 * stepdown) break;
    z.push_back(h);
  }
  z.push_back(bottom);
  return z;
}

// Appends one loop: rapid above its start, plunge, the loop (closed back to its start) and a retract.
void cut_loop(const std::vector<Vec2>& loop, size_t start, double z, const Tool& tool, double safe_z,
              ToolpathPass& pass) {
  const Vec2& s = loop[start];
  pass.moves.push_back({Vec3(s.x(), s.y(), safe_z), MoveType::Rapid, 0.0});
  pass.moves.push_back({Vec3(s.x(), s.y(), z), MoveType::Plunge, tool.plunge_feed});
  for (size_t k = 1; k <= loop.size(); ++k) {
    const Vec2& p = loop[(start + k) % loop.size()];
    pass.moves.push_back({Vec3(p.x(), p.y(), z), MoveType::Feed, tool.feed});
  }
  pass.moves.push_back({Vec3(s.x(), s.y(), safe_z), MoveType::Rapid, 0.0});
}

// Loops of one layer in nearest-first order from `at`, each entered at its point nearest to the tool.
void cut_layer(std::vector<OffsetLoop>& loops, double z, const Tool& tool, double safe_z, Vec2& at,
               ToolpathPass& pass) {
  std::vector<bool> done(loops.size(), false);
  for (size_t n = 0; n < loops.size(); ++n) {
    size_t best_loop = 0, best_point = 0;
    double best = INFINITY;
    for (size_t i = 0; i < loops.size(); ++i) {
      if (done[i]) continue;
      for (size_t k = 0; k < loops[i].points.size(); ++k) {
        const double d = (loops[i].points[k] - at).squaredNorm();
        if (d < best) best = d, best_loop = i, best_point = k;
      }
    }
    done[best_loop] = true;
    cut_loop(loops[best_loop].points, best_point, z, tool, safe_z, pass);
    at = loops[best_loop].points[best_point];
  }
}

}  // namespace

Toolpath contour_toolpath(const Mesh& mesh, const Tool& tool, const ContourOptions& options,
                          const PlanProgress& progress) {
  if (tool.cutter.type != CutterType::FlatEnd)
    throw Error("contour", std::string("needs a flat end mill, got a ") + cutter_type_name(tool.cutter.type) + " cutter");
  if (!(options.stepdown > 0.0) || !std::isfinite(options.stepdown))
    throw Error("contour", "the stepdown must be a positive number");
  if (!(options.allowance >= 0.0) || !std::isfinite(options.allowance))
    throw Error("contour", "the allowance must be zero or positive");
  if (mesh.faces.empty()) throw Error("contour", "the mesh is empty");
  // Each layer slices the triangles and offsets its section, a full turn of arc at the arc tolerance per loop.
  const double n_levels = step_count(mesh.bbox.size().z(), options.stepdown);
  const double distance = tool.cutter.radius() + options.allowance;
  const double turn = M_PI / std::acos(std::max(-1.0, 1.0 - std::max(options.arc_tolerance / 2.5, 1e-6) / distance));
  check_work("contour", {n_levels * (double(mesh.faces.size()) + turn), n_levels * turn,
                         count_text(n_levels, "layers") + " x " +
                             count_text(double(mesh.faces.size()), "triangles"),
                         "plane-triangle intersections and arc points"},
             mesh.bbox.size().x(), mesh.bbox.size().y());

  const std::vector<double> z = layer_heights(mesh, options.stepdown);
  const std::vector<SliceLayer> sections = slice_mesh(mesh, z);
  // The cutter's body rises from its tip: at each layer it must clear every section above, so each layer offsets
  // the union of the sections from the top down to it (equal to the section itself when nothing overhangs).
  std::vector<std::vector<Contour>> shadow(z.size());
  for (size_t k = 0; k < z.size(); ++k)
    shadow[k] = k == 0 ? union_regions({}, sections[0].contours) : union_regions(shadow[k - 1], sections[k].contours);
  std::vector<std::vector<OffsetLoop>> loops(z.size());
  for_each_index(size_t(0), z.size(), [&](size_t k) {
    loops[k] = offset_region(shadow[k], distance, options.arc_tolerance);
    // Climb milling with a clockwise spindle keeps the material on the cutter's right: clockwise around material,
    // counter-clockwise inside holes, i.e. every offset loop reversed.
    if (options.climb)
      for (OffsetLoop& l : loops[k]) std::reverse(l.points.begin(), l.points.end());
  });

  Toolpath tp;
  tp.strategy = "contour";
  tp.tool = tool;
  tp.safe_z = mesh.bbox.max.z() + options.safe_clearance;
  tp.clearance_z = tp.safe_z;
  const Vec3 centre = 0.5 * (mesh.bbox.min + mesh.bbox.max);
  tp.start = Vec3(centre.x(), centre.y(), tp.clearance_z);
  Vec2 at = centre.head<2>();
  for (size_t k = 0; k < z.size(); ++k) {
    if (progress && !progress(double(k) / double(z.size()))) throw Error("plan", "cancelled");
    if (loops[k].empty()) continue;
    ToolpathPass pass;
    pass.name = "contour z=" + std::to_string(z[k]);
    cut_layer(loops[k], z[k], tool, tp.safe_z, at, pass);
    tp.passes.push_back(std::move(pass));
  }
  if (progress) progress(1.0);
  return tp;
}

Job plan_contour(const Mesh& mesh, const PlanParams& params, const PlanProgress& progress) {
  ContourOptions o;
  o.stepdown = std::isnan(params.stepdown) ? params.tool.stepdown : params.stepdown;
  o.allowance = params.allowance;
  o.arc_tolerance = params.tolerance;
  o.safe_clearance = params.safe_clearance;
  return {contour_toolpath(mesh, params.tool, o, progress)};
}

}  // namespace rosmill::core
