#include "rosmill/verify/deviation_image.hpp"

#include <algorithm>
#include <cstdio>

namespace rosmill::core::verify {
namespace {

constexpr int kMapPixels = 800, kMargin = 16, kLegendWidth = 430, kScale = 2;
constexpr Rgb kWhite{255, 255, 255}, kBlack{0, 0, 0}, kInk{30, 30, 30};

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
  char buf[96];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

// The report's figures, a line each (short enough for the legend's width).
std::vector<std::string> figures(const DeviationGrid& grid, const DeviationReport& r) {
  const stock::GridSpec& g = grid.grid;
  std::vector<std::string> lines;
  lines.push_back(fmt("%.0f x %.0f cells of %g mm", g.nx, g.ny, g.cell));
  if (r.gouged) {
    lines.push_back(fmt("max gouge %.4g mm", r.max_gouge_mm));
    lines.push_back(fmt("at x %.2f y %.2f z %.3f", r.gouge_at.x(), r.gouge_at.y(), r.gouge_at.z()));
    if (r.gouge_source) lines.push_back(std::string(r.from_gcode ? "line " : "move ") + std::to_string(r.gouge_source));
  } else {
    lines.push_back("no gouge");
  }
  lines.push_back(fmt("max rest %.4g mm", r.max_rest_mm));
  lines.push_back(fmt("mean rest %.4g mm", r.mean_rest_mm));
  if (r.scallop_theory_mm >= 0) lines.push_back(fmt("scallop %.4g (theory %.4g)", r.scallop_mm, r.scallop_theory_mm));
  else lines.push_back(fmt("scallop %.4g mm", r.scallop_mm));
  lines.push_back(fmt("unreached %.4g mm2", r.unreached_area_mm2));
  if (r.rapid_cut_cells) lines.push_back(fmt("rapids cut %.0f cells", static_cast<double>(r.rapid_cut_cells)));
  return lines;
}

}  // namespace

RgbImage deviation_image(const DeviationGrid& grid, const DeviationReport& report) {
  const stock::GridSpec& g = grid.grid;
  const int longest = std::max(g.nx, g.ny);
  const int step = std::max(1, (longest + kMapPixels - 1) / kMapPixels);       // cells a pixel (large grids)
  const int zoom = step > 1 ? 1 : std::clamp(kMapPixels / longest, 1, 8);     // pixels a cell (small grids)
  const int w = (g.nx + step - 1) / step * zoom, h = (g.ny + step - 1) / step * zoom;
  const std::vector<DeviationBand> bands = deviation_bands(grid.tolerance);
  const std::vector<std::string> lines = figures(grid, report);
  const int line_h = 11 * kScale, legend_h = kMargin + 3 * line_h + static_cast<int>(bands.size()) * line_h +
                                             line_h + static_cast<int>(lines.size()) * line_h + kMargin;
  RgbImage img(w + 3 * kMargin + kLegendWidth, std::max(h + 2 * kMargin + 2 * line_h, legend_h), kWhite);

  // The map, row 0 of the grid at the bottom.
  for (int j = 0; j < g.ny; j += step)
    for (int i = 0; i < g.nx; i += step) {
      const long c = worst_cell(grid, i, j, step);
      const Rgb colour = bands[c < 0 ? bands.size() - 1 : deviation_band(grid.deviation[c], grid.cut[c], grid.tolerance)].colour;
      img.fill(kMargin + i / step * zoom, kMargin + h - (j / step + 1) * zoom, zoom, zoom, colour);
    }
  img.frame(kMargin - 1, kMargin - 1, w + 2, h + 2, kBlack);
  img.text(kMargin, kMargin + h + line_h / 2,
           fmt("x %.4g to %.4g mm, y %.4g", g.x0, g.x0 + g.nx * g.cell, g.y0) + fmt(" to %.4g mm", g.y0 + g.ny * g.cell),
           kScale, kInk);
  if (report.gouged) {  // ring the deepest gouge, black outside white so it shows on any colour
    const double px = kMargin + (report.gouge_at.x() - g.x0) / (g.cell * step) * zoom;
    const double py = kMargin + h - (report.gouge_at.y() - g.y0) / (g.cell * step) * zoom;
    img.ring(static_cast<int>(px), static_cast<int>(py), 9, 12, kBlack);
    img.ring(static_cast<int>(px), static_cast<int>(py), 7, 9, kWhite);
  }

  // The legend and the figures.
  const int x = w + 2 * kMargin + kMargin;
  int y = kMargin;
  img.text(x, y, "deviation (mm)", kScale, kInk);
  y += line_h;
  img.text(x, y, "= machined - design", kScale, kInk);
  y += 2 * line_h;
  for (const DeviationBand& b : bands) {
    img.fill(x, y - 2, 28, 2 + 7 * kScale, b.colour);
    img.frame(x, y - 2, 28, 2 + 7 * kScale, kBlack);
    img.text(x + 36, y, b.label, kScale, kInk);
    y += line_h;
  }
  y += line_h;
  for (const std::string& l : lines) {
    img.text(x, y, l, kScale, kInk);
    y += line_h;
  }
  return img;
}

void write_deviation_png(const std::string& path, const DeviationGrid& grid, const DeviationReport& report) {
  write_png(path, deviation_image(grid, report));
}

}  // namespace rosmill::core::verify
