#include "rosmill/verify/tool_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "rosmill/parallel.hpp"
#include "rosmill/scan/mesh_distance.hpp"

namespace rosmill::core::verify {
namespace {

// How far the tool at `tip` along `axis` goes into the design: the ball's depth, and the body's.
struct Depth {
  double ball = 0, body = 0;
};

Depth tool_depth(const scan::MeshDistance& distance, const Tool& tool, double allowance, const Vec3& tip,
                 const Vec3& axis, double step) {
  const auto within = [&](const Vec3& p, double r) {
    scan::SurfaceDistance d;
    return distance.query_within(p, r, d) ? r - std::abs(d.signed_distance) : 0.0;
  };
  const double R = tool.cutter.radius(), shank = 0.5 * tool.cutter.shank_diameter, holder = 0.5 * tool.holder_mm();
  const double flutes = tool.cutter.flute_length, stick_out = tool.stick_out_mm();
  Depth d;
  d.ball = std::max(0.0, within(tip + R * axis, R + allowance));
  for (double s = R + step; s <= stick_out; s += step)
    d.body = std::max(d.body, within(tip + s * axis, s <= flutes ? R : shank));
  // The holder: as long again as its radius twice (a collet nut), sampled the same way.
  for (double s = stick_out; s <= stick_out + 2 * holder; s += step)
    d.body = std::max(d.body, within(tip + s * axis, holder));
  return d;
}

}  // namespace

ToolClearance check_tool_clearance(const Mesh& design, const Job& job, double allowance, double step) {
  ToolClearance out;
  const scan::MeshDistance distance(design);
  std::mutex m;
  for (size_t t = 0; t < job.size(); ++t) {
    const Toolpath& tp = job[t];
    if (!tp.multi_axis()) continue;
    const double widest =
        std::max({tp.tool.cutter.radius(), 0.5 * tp.tool.cutter.shank_diameter, 0.5 * tp.tool.holder_mm()});
    out.sampling_mm = std::max(out.sampling_mm, widest - std::sqrt(std::max(0.0, widest * widest - step * step / 4)));
    for (size_t p = 0; p < tp.passes.size(); ++p) {
      const ToolpathPass& pass = tp.passes[p];
      if (pass.axes.size() != pass.moves.size()) continue;
      const int n = static_cast<int>(pass.moves.size());
      for_each_piece(0, n, 16, [&](int begin, int end) {
        ToolClearance local;
        for (int k = begin; k < end; ++k) {
          const Vec3 from = k > 0 ? pass.moves[k - 1].to : pass.moves[k].to;
          const Vec3 from_axis = k > 0 ? pass.axes[k - 1] : pass.axes[k];
          for (const double f : {0.5, 1.0}) {
            const Vec3 tip = from + f * (pass.moves[k].to - from);
            const Vec3 axis = (from_axis + f * (pass.axes[k] - from_axis)).normalized();
            const Depth d = tool_depth(distance, tp.tool, allowance, tip, axis, step);
            ++local.positions;
            if (std::max(d.ball, d.body) > std::max(local.ball_depth_mm, local.body_depth_mm))
              local.deepest =
                  "toolpath " + std::to_string(t + 1) + ", pass " + std::to_string(p) + ", move " + std::to_string(k);
            local.ball_depth_mm = std::max(local.ball_depth_mm, d.ball);
            local.body_depth_mm = std::max(local.body_depth_mm, d.body);
          }
        }
        const std::lock_guard<std::mutex> lock(m);
        if (std::max(local.ball_depth_mm, local.body_depth_mm) > std::max(out.ball_depth_mm, out.body_depth_mm))
          out.deepest = local.deepest;
        out.ball_depth_mm = std::max(out.ball_depth_mm, local.ball_depth_mm);
        out.body_depth_mm = std::max(out.body_depth_mm, local.body_depth_mm);
        out.positions += local.positions;
      });
    }
  }
  return out;
}

}  // namespace rosmill::core::verify
