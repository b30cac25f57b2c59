#include "operation_engagement.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rosmill/cutter/chip_thinning.hpp"
#include "rosmill/error.hpp"

namespace rosmill::core::job {
namespace {

// The view's heights read onto a finer grid: each fine cell takes the coarse cell holding its centre.
stock::HeightField finer(const stock::HeightField& view, const stock::GridSpec& grid) {
  stock::HeightField out;
  out.grid = grid;
  out.bottom = view.bottom;
  out.top.assign(grid.cells(), stock::kNoMaterial);
  out.cut_by.assign(grid.cells(), stock::HeightField::kNoMove);
  const stock::GridSpec& g = view.grid;
  for (int j = 0; j < grid.ny; ++j) {
    const double fj = std::floor((grid.cy(j) - g.y0) / g.cell);
    if (!(fj >= 0 && fj < g.ny)) continue;
    for (int i = 0; i < grid.nx; ++i) {
      const double fi = std::floor((grid.cx(i) - g.x0) / g.cell);
      if (fi >= 0 && fi < g.nx) out.top[grid.index(i, j)] = view.top[g.index(int(fi), int(fj))];
    }
  }
  return out;
}

}  // namespace

void EngagementStock::prepare(const stock::MachineProgram& program, const stock::InProcessStock& stock,
                              const SetupFrame& frame, size_t setup_index) {
  if (setup_ != setup_index) {
    const stock::HeightField view = stock.view(frame);
    const stock::GridSpec& g = view.grid;
    const Vec2 lo(g.x0, g.y0), hi(g.x0 + g.nx * g.cell, g.y0 + g.ny * g.cell);
    const verify::EngagementOptions defaults;
    field_ = finer(view, verify::engagement_grid_over(lo, hi, verify::engagement_cell(program), defaults.max_cells));
    setup_ = setup_index;
  }
}

verify::EngagementReport EngagementStock::measure(const stock::MachineProgram& program) {
  if (!setup_) throw Error("engagement", "measured before the stock was read");
  return verify::measure_engagement(program, field_);
}

size_t set_feeds_from_engagement(Job& toolpaths, const std::vector<float>& move_deg, double max_feed) {
  size_t k = 0, set = 0;
  for (Toolpath& tp : toolpaths) {
    Vec3 at = tp.start;
    for (ToolpathPass& pass : tp.passes)
      for (Move& mv : pass.moves) {
        if (k >= move_deg.size())
          throw Error("feeds from engagement", "the engagement has " + std::to_string(move_deg.size()) +
                                                   " moves, fewer than the toolpaths");
        const bool travels = (mv.to - at).head<2>().norm() >= 1e-6;
        if (mv.type == MoveType::Feed && travels) {
          mv.feed = feed_for_engagement(tp.tool, std::min(180.0, double(move_deg[k])), max_feed);
          ++set;
        }
        at = mv.to;
        ++k;
      }
  }
  return set;
}

}  // namespace rosmill::core::job
