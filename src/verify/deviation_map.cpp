#include "rosmill/verify/deviation_map.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/number_text.hpp"

namespace rosmill::core::verify {
namespace {

// Four gouge bands (deepest first), on the design, four rest bands (least first), not cut, no design.
constexpr Rgb kColours[] = {{90, 0, 60},    {170, 0, 20},  {235, 70, 50},  {255, 170, 150}, {40, 170, 70},
                            {175, 215, 255}, {90, 150, 235}, {35, 80, 200}, {10, 25, 120},   {205, 205, 205},
                            {70, 70, 70}};
constexpr size_t kOnDesign = 4, kNotCut = 9, kNoDesign = 10;

std::string mm(double v) { return significant_text(v, 6); }

}  // namespace

std::vector<DeviationBand> deviation_bands(double tol) {
  const double d[4] = {tol, 10 * tol, 100 * tol, 1000 * tol};
  std::vector<DeviationBand> bands;
  bands.push_back({kColours[0], "gouge > " + mm(d[3])});
  for (int k = 2; k >= 0; --k) bands.push_back({kColours[3 - k], "gouge " + mm(d[k]) + " - " + mm(d[k + 1])});
  bands.push_back({kColours[kOnDesign], "on design +/- " + mm(tol)});
  for (int k = 0; k < 3; ++k) bands.push_back({kColours[5 + k], "rest " + mm(d[k]) + " - " + mm(d[k + 1])});
  bands.push_back({kColours[8], "rest > " + mm(d[3])});
  bands.push_back({kColours[kNotCut], "not cut"});
  bands.push_back({kColours[kNoDesign], "no design"});
  return bands;
}

size_t deviation_band(double deviation, bool cut, double tol) {
  if (std::isnan(deviation)) return kNoDesign;
  const double size = std::abs(deviation);
  if (size <= tol) return kOnDesign;
  if (deviation > 0 && !cut) return kNotCut;
  const size_t decade = size < 10 * tol ? 0 : size < 100 * tol ? 1 : size < 1000 * tol ? 2 : 3;
  return deviation < 0 ? 3 - decade : 5 + decade;
}

long worst_cell(const DeviationGrid& grid, int i, int j, int step) {
  const stock::GridSpec& g = grid.grid;
  long worst = -1;
  for (int v = j; v < std::min(g.ny, j + step); ++v)
    for (int u = i; u < std::min(g.nx, i + step); ++u) {
      const long c = static_cast<long>(g.index(u, v));
      const float d = grid.deviation[c];
      if (std::isnan(d)) continue;
      if (worst < 0) { worst = c; continue; }
      const float w = grid.deviation[worst];
      // A gouge (below the tolerance) beats any other cell; among gouges the deepest, among the others the highest.
      const bool gd = d < -grid.tolerance, gw = w < -grid.tolerance;
      if ((gd && (!gw || d < w)) || (!gd && !gw && d > w)) worst = c;
    }
  return worst;
}

std::vector<DeviationPoint> deviation_points(const DeviationGrid& grid, size_t max_points) {
  const stock::GridSpec& g = grid.grid;
  int step = 1;
  while (max_points > 0 && static_cast<size_t>((g.nx + step - 1) / step) * ((g.ny + step - 1) / step) > max_points)
    ++step;
  std::vector<DeviationPoint> points;
  for (int j = 0; j < g.ny; j += step)
    for (int i = 0; i < g.nx; i += step) {
      const long c = worst_cell(grid, i, j, step);
      if (c < 0) continue;
      const int u = static_cast<int>(c % g.nx), v = static_cast<int>(c / g.nx);
      DeviationPoint p;
      p.position = Vec3(g.cx(u), g.cy(v), grid.machined[c]);
      p.deviation = grid.deviation[c];
      p.colour = kColours[deviation_band(p.deviation, grid.cut[c], grid.tolerance)];
      points.push_back(p);
    }
  return points;
}

}  // namespace rosmill::core::verify
