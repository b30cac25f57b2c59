#include "rosmill/verify/deviation_image.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "formatted.hpp"
#include "rosmill/verify/deviation_map.hpp"

namespace rosmill::core::verify {
namespace {

constexpr int kMapPixels = 800;
constexpr Rgb kOutline{0, 0, 0};

// The report's figures, a line each (short enough for the legend's width).
std::vector<std::string> figures(const DeviationGrid& grid, const DeviationReport& r) {
  const stock::GridSpec& g = grid.grid;
  std::vector<std::string> lines;
  lines.push_back(formatted("%.0f x %.0f cells of %g mm", g.nx, g.ny, g.cell));
  if (r.gouged) {
    lines.push_back(formatted("max gouge %.4g mm (ringed)", r.max_gouge_mm));
    lines.push_back(formatted("at x %.2f y %.2f z %.3f", r.gouge_at.x(), r.gouge_at.y(), r.gouge_at.z()));
    if (r.gouge_source) lines.push_back(std::string(r.from_gcode ? "line " : "move ") + std::to_string(r.gouge_source));
  } else {
    lines.push_back("no gouge");
  }
  lines.push_back(formatted("max rest %.4g mm", r.max_rest_mm));
  lines.push_back(formatted("mean rest %.4g mm", r.mean_rest_mm));
  if (r.scallop_theory_mm >= 0) lines.push_back(formatted("scallop %.4g mm (theory %.4g)", r.scallop_mm, r.scallop_theory_mm));
  else lines.push_back(formatted("scallop %.4g mm", r.scallop_mm));
  lines.push_back(formatted("unreached %.4g mm2", r.unreached_area_mm2));
  if (r.rapid_cut_cells) lines.push_back(formatted("rapids cut %.0f cells", static_cast<double>(r.rapid_cut_cells)));
  return lines;
}

// The cells in blocks of `step` x `step`, each its worst cell's colour; a run of blocks of one colour along a row
// is one rectangle (a flat floor is a few hundred rectangles, not a million).
void draw_cells(picture::MapPlot& plot, const DeviationGrid& grid, int step) {
  const stock::GridSpec& g = grid.grid;
  const std::vector<DeviationBand> bands = deviation_bands(grid.tolerance);
  auto band_of = [&](int i, int j) {
    const long c = worst_cell(grid, i, j, step);
    return c < 0 ? bands.size() - 1 : deviation_band(grid.deviation[c], grid.cut[c], grid.tolerance);
  };
  for (int j = 0; j < g.ny; j += step) {
    const double y0 = g.y0 + j * g.cell, y1 = g.y0 + std::min(g.ny, j + step) * g.cell;
    for (int i = 0; i < g.nx;) {
      const size_t band = band_of(i, j);
      int end = i + step;
      while (end < g.nx && band_of(end, j) == band) end += step;
      plot.fill_rect(g.x0 + i * g.cell, y0, g.x0 + std::min(g.nx, end) * g.cell, y1, bands[band].colour);
      i = end;
    }
  }
}

// A cloud design's extent seen from above at the grid's resolution: the cell edges between a cell where the design has a height
// and one where it has none (or the grid's border), joined into straight runs.
void draw_cells_outline(picture::MapPlot& plot, const DeviationGrid& grid) {
  const stock::GridSpec& g = grid.grid;
  auto part = [&](int i, int j) {
    return i >= 0 && j >= 0 && i < g.nx && j < g.ny && !std::isnan(grid.design[g.index(i, j)]);
  };
  // Along rows: the edge below cell (i, j); along columns: the edge left of cell (i, j).
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i < g.nx;) {
      if (part(i, j) == part(i, j - 1)) { ++i; continue; }
      int end = i + 1;
      while (end < g.nx && part(end, j) != part(end, j - 1)) ++end;
      const double y = g.y0 + j * g.cell;
      plot.polyline({Vec2(g.x0 + i * g.cell, y), Vec2(g.x0 + end * g.cell, y)}, false, kOutline, 1.5);
      i = end;
    }
  for (int i = 0; i <= g.nx; ++i)
    for (int j = 0; j < g.ny;) {
      if (part(i, j) == part(i - 1, j)) { ++j; continue; }
      int end = j + 1;
      while (end < g.ny && part(i, end) != part(i - 1, end)) ++end;
      const double x = g.x0 + i * g.cell;
      plot.polyline({Vec2(x, g.y0 + j * g.cell), Vec2(x, g.y0 + end * g.cell)}, false, kOutline, 1.5);
      j = end;
    }
}

}  // namespace

picture::MapPicture deviation_picture(const DeviationGrid& grid, const DeviationReport& report,
                                      const std::vector<Contour>& outline, const picture::MapCaption& caption) {
  const stock::GridSpec& g = grid.grid;
  picture::MapLegend legend;
  legend.heading = {"deviation (mm)", "= machined - design"};
  legend.bands = deviation_bands(grid.tolerance);
  legend.figures = figures(grid, report);
  picture::MapPlot plot(g.x0, g.y0, g.x0 + g.nx * g.cell, g.y0 + g.ny * g.cell, caption, legend, "deviation map",
                        kMapPixels);
  const int longest = std::max(g.nx, g.ny);
  draw_cells(plot, grid, std::max(1, (longest + kMapPixels - 1) / kMapPixels));
  if (outline.empty()) draw_cells_outline(plot, grid);
  for (const Contour& c : outline) plot.polyline(c.points, c.closed, kOutline, 1.5);
  if (report.gouged) plot.ring(report.gouge_at.x(), report.gouge_at.y());
  return plot.finish();
}

void write_deviation_png(const std::string& path, const DeviationGrid& grid, const DeviationReport& report,
                         const std::vector<Contour>& outline, const picture::MapCaption& caption) {
  deviation_picture(grid, report, outline, caption).canvas.write_png(path);
}

}  // namespace rosmill::core::verify
