#include "rosmill/verify/inspection_image.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "rosmill/cloud/cloud_grid.hpp"
#include "rosmill/error.hpp"
#include "rosmill/verify/deviation_map.hpp"
#include "formatted.hpp"

namespace rosmill::core::verify {
namespace {

constexpr int kMapPixels = 800;
constexpr size_t kBandsOfAScan = 9;  // a scan point is on the part and measured: never "not cut" nor "no design"

// The median nearest-neighbour distance of the scan (mm); 0 for fewer than two points.
double point_spacing(const std::vector<Vec3>& points) {
  if (points.size() < 2) return 0;
  Box3 box;
  for (const Vec3& p : points) box.add(p);
  const double area = std::max(box.size().x() * box.size().y(), 1e-6);
  return spacing_quantile(CloudGrid(points, auto_grid_cell(points.size(), area)), 0.5);
}

std::vector<std::string> figures(const scan::InspectionReport& r, double tolerance, double spacing) {
  const double n = static_cast<double>(r.points.size());
  std::vector<std::string> lines;
  lines.push_back(formatted("%.0f points, drawn %.3g mm across", n, spacing));
  lines.push_back(formatted("largest excess %.4g mm", r.largest_excess.distance));
  lines.push_back(formatted("  at x %.2f y %.2f z %.3f", r.largest_excess.place.x(), r.largest_excess.place.y(),
                      r.largest_excess.place.z()));
  lines.push_back(formatted("largest deficit %.4g mm", r.largest_deficit.distance));
  lines.push_back(formatted("  at x %.2f y %.2f z %.3f", r.largest_deficit.place.x(), r.largest_deficit.place.y(),
                      r.largest_deficit.place.z()));
  lines.push_back(formatted("mean %.4g mm, rms %.4g mm", r.mean, r.rms));
  if (n > 0) lines.push_back(formatted("within +/- %g mm: %.1f %%", tolerance, 100.0 * r.within_tolerance / n));
  return lines;
}

}  // namespace

picture::MapPicture inspection_picture(const scan::InspectionReport& report, double tolerance,
                                       const std::vector<Contour>& outline, const picture::MapCaption& caption) {
  if (report.points.empty()) throw Error("inspection map", "the scan has no points to draw");
  if (report.deviations.size() != report.points.size())
    throw Error("inspection map", std::to_string(report.deviations.size()) + " deviations for " +
                                      std::to_string(report.points.size()) + " points");
  const double spacing = point_spacing(report.points);
  Box3 box;
  for (const Vec3& p : report.points) box.add(p);
  for (const Contour& c : outline)
    for (const Vec2& q : c.points) box.add(Vec3(q.x(), q.y(), 0));
  // A margin of a disc and a little more, so that no point sits on the frame; a millimetre for a single point.
  const double pad = std::max({spacing, 0.02 * std::max(box.size().x(), box.size().y()), box.size().norm() > 0 ? 0.0 : 1.0});

  picture::MapLegend legend;
  legend.heading = {"deviation (mm)", "= scan - design"};
  legend.bands = deviation_bands(tolerance);
  legend.bands.resize(kBandsOfAScan);
  legend.figures = figures(report, tolerance, spacing);
  picture::MapPlot plot(box.min.x() - pad, box.min.y() - pad, box.max.x() + pad, box.max.y() + pad, caption, legend,
                        "inspection map", kMapPixels);
  std::vector<size_t> order(report.points.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::abs(report.deviations[a]) < std::abs(report.deviations[b]);
  });
  for (const size_t k : order) {
    if (!std::isfinite(report.deviations[k])) continue;  // not measured: no band to draw it in
    const Vec3& p = report.points[k];
    plot.disc(p.x(), p.y(), spacing / 2, legend.bands[deviation_band(report.deviations[k], true, tolerance)].colour);
  }
  for (const Contour& c : outline) plot.polyline(c.points, c.closed, Rgb{0, 0, 0}, 1.5);
  return plot.finish();
}

void write_inspection_png(const std::string& path, const scan::InspectionReport& report, double tolerance,
                          const std::vector<Contour>& outline, const picture::MapCaption& caption) {
  inspection_picture(report, tolerance, outline, caption).canvas.write_png(path);
}

}  // namespace rosmill::core::verify
