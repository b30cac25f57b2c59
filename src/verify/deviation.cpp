#include "rosmill/verify/deviation.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/cutter/contact.hpp"

namespace rosmill::core::verify {
namespace {

constexpr double kFlatSlope = 0.2;  // about 11 degrees

// The profile of the finishing tool (the tool of the last move).
CutterProfile finishing_profile(const stock::MachineProgram& program) {
  return CutterProfile(program.moves.empty() ? Cutter{} : program.tools[program.moves.back().tool].cutter);
}

double stepover_of(const stock::MachineProgram& program, const CompareOptions& options) {
  return options.stepover > 0 ? options.stepover : program.finishing_stepover;
}

// Cells where the design is nearly flat (slope under `max_slope`) everywhere within `radius`: there the cutter's
// whole footprint sits on a floor, so the material left between passes is a scallop comparable with the
// flat-floor theory; next to a wall or on a slope it is something else (a fillet the cutter cannot enter).
std::vector<uint8_t> flat_floor_cells(const std::vector<float>& z, const stock::GridSpec& g, double max_slope,
                                      double radius) {
  const int nx = g.nx, ny = g.ny;
  // Steep (or unknown) cells, by differences over the neighbours that exist.
  std::vector<uint8_t> steep(g.cells(), 0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int i0 = std::max(0, i - 1), i1 = std::min(nx - 1, i + 1), j0 = std::max(0, j - 1), j1 = std::min(ny - 1, j + 1);
      const double dx = i1 > i0 ? (z[g.index(i1, j)] - z[g.index(i0, j)]) / ((i1 - i0) * g.cell) : 0.0;
      const double dy = j1 > j0 ? (z[g.index(i, j1)] - z[g.index(i, j0)]) / ((j1 - j0) * g.cell) : 0.0;
      steep[g.index(i, j)] = !(dx * dx + dy * dy <= max_slope * max_slope);  // NaN counts as steep
    }
  // Dilate the steep cells by a square of half-width k: rows, then columns, with running counts.
  const int k = static_cast<int>(std::ceil(radius / g.cell));
  auto dilate = [k](std::vector<uint8_t>& v, int n, int lines, auto at) {
    std::vector<int> prefix(n + 1);
    std::vector<uint8_t> out(n);
    for (int line = 0; line < lines; ++line) {
      for (int q = 0; q < n; ++q) prefix[q + 1] = prefix[q] + v[at(line, q)];
      for (int q = 0; q < n; ++q) out[q] = prefix[std::min(n, q + k + 1)] - prefix[std::max(0, q - k)] > 0;
      for (int q = 0; q < n; ++q) v[at(line, q)] = out[q];
    }
  };
  dilate(steep, nx, ny, [&](int line, int q) { return g.index(q, line); });
  dilate(steep, ny, nx, [&](int line, int q) { return g.index(line, q); });
  for (uint8_t& c : steep) c = !c;
  return steep;
}

}  // namespace

double scallop_theory(const Cutter& cutter, double stepover) {
  const CutterProfile cp(cutter);
  return cp.height(std::min(cp.R, 0.5 * stepover));
}

double scallop_window(const stock::MachineProgram& program, const CompareOptions& options, double cell) {
  const double s = stepover_of(program, options);
  return (s > 0 ? 0.5 * s : 0.5 * finishing_profile(program).R) + 0.5 * cell;
}

DeviationReport compare(const stock::HeightField& stock, const std::vector<float>& design,
                        const stock::MachineProgram& program,
                        const stock::SimulationResult& sim, const CompareOptions& options, DeviationGrid* grid) {
  const stock::GridSpec& g = stock.grid;
  DeviationReport r;
  r.cells = g.cells();
  const double tol = options.tolerance;
  r.from_gcode = program.from_gcode;
  r.stepover_mm = stepover_of(program, options);
  const CutterProfile finish = finishing_profile(program);
  if (r.stepover_mm > 0) r.scallop_theory_mm = scallop_theory(program.tools[sim.finishing_tool].cutter, r.stepover_mm);
  const double window = scallop_window(program, options, g.cell), window_d2 = window * window;
  const bool traced = sim.finish_axis_d2.size() == g.cells();
  if (grid) {
    grid->grid = g;
    grid->machined = stock.top;
    grid->design = design;
    grid->deviation.assign(g.cells(), std::numeric_limits<float>::quiet_NaN());
    grid->cut.resize(g.cells());
    for (size_t c = 0; c < g.cells(); ++c) grid->cut[c] = stock.cut_by[c] != stock::HeightField::kNoMove;
    grid->tolerance = tol;
  }
  const std::vector<uint8_t> flat = flat_floor_cells(design, g, kFlatSlope, finish.R);
  double rest_sum = 0.0;
  size_t gouge_cell = 0, unreached = 0;
  for (size_t c = 0; c < g.cells(); ++c) {
    if (std::isnan(design[c])) continue;
    ++r.compared_cells;
    const double dev = static_cast<double>(stock.top[c]) - design[c];
    if (grid) grid->deviation[c] = static_cast<float>(dev);
    if (dev < -tol) {
      ++r.gouge_cells;
      if (-dev > r.max_gouge_mm) { r.max_gouge_mm = -dev; gouge_cell = c; r.gouged = true; }
      continue;
    }
    if (dev <= 0) continue;
    rest_sum += dev;
    r.max_rest_mm = std::max(r.max_rest_mm, dev);
    if (dev > tol && stock.cut_by[c] == stock::HeightField::kNoMove) ++unreached;
    const bool by_finisher =
        stock.cut_by[c] != stock::HeightField::kNoMove && program.moves[stock.cut_by[c]].tool == sim.finishing_tool;
    if (traced && by_finisher && sim.finish_axis_d2[c] <= window_d2 && flat[c]) r.scallop_mm = std::max(r.scallop_mm, dev);
  }
  if (r.compared_cells) r.mean_rest_mm = rest_sum / r.compared_cells;
  r.unreached_area_mm2 = unreached * g.cell * g.cell;
  if (r.gouged) {
    const int i = static_cast<int>(gouge_cell % g.nx), j = static_cast<int>(gouge_cell / g.nx);
    r.gouge_at = Vec3(g.cx(i), g.cy(j), stock.top[gouge_cell]);
    r.gouge_move = stock.cut_by[gouge_cell];
    if (r.gouge_move != stock::HeightField::kNoMove) r.gouge_source = program.moves[r.gouge_move].source;
  }
  r.rapid_cut_cells = sim.rapid_cut_cells;
  if (sim.first_rapid_cut != stock::HeightField::kNoMove)
    r.first_rapid_cut_source = program.moves[sim.first_rapid_cut].source;
  return r;
}

}  // namespace rosmill::core::verify
