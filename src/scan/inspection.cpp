#include "rosmill/scan/inspection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "rosmill/error.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/scan/mesh_distance.hpp"

namespace rosmill::core::scan {
namespace {

void fill_histogram(InspectionReport& r, int bins) {
  const auto [low, high] = std::minmax_element(r.deviations.begin(), r.deviations.end());
  r.histogram_low = *low;
  r.bin_width = std::max(*high - *low, 1e-9) / bins;
  r.histogram.assign(size_t(bins), 0);
  for (double d : r.deviations)
    ++r.histogram[std::min(size_t(bins - 1), size_t((d - r.histogram_low) / r.bin_width))];
}

}  // namespace

void InspectionOptions::check() const {
  if (!(tolerance >= 0) || !std::isfinite(tolerance)) throw Error("inspection option tolerance", "must be >= 0 mm");
  if (bins < 1 || bins > 1000) throw Error("inspection option bins", "must lie in [1, 1000]");
  registration.check();
}

InspectionReport inspect_registered(const Mesh& design, const std::vector<Vec3>& points,
                                    const InspectionOptions& o) {
  o.check();
  if (points.empty()) throw Error("inspection", "the scan has no point");
  const MeshDistance distance(design);
  InspectionReport r;
  r.points = points;
  r.deviations.resize(points.size());
  for_each_index(size_t(0), points.size(),
                 [&](size_t i) { r.deviations[i] = distance.query(points[i]).signed_distance; });
  double sum = 0, sum_sq = 0;
  size_t most = 0, least = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const double d = r.deviations[i];
    sum += d;
    sum_sq += d * d;
    if (d > r.deviations[most]) most = i;
    if (d < r.deviations[least]) least = i;
    if (d > o.tolerance) ++r.above_tolerance;
    else if (d < -o.tolerance) ++r.below_tolerance;
    else ++r.within_tolerance;
  }
  r.mean = sum / double(points.size());
  r.rms = std::sqrt(sum_sq / double(points.size()));
  r.largest_excess = {r.deviations[most], points[most]};
  r.largest_deficit = {r.deviations[least], points[least]};
  fill_histogram(r, o.bins);
  return r;
}

InspectionReport inspect(const Mesh& design, const PointCloud& scan, const InspectionOptions& o) {
  o.check();
  const RegistrationResult registration = register_design(design, scan, o.registration);
  InspectionReport r =
      inspect_registered(design, transformed_points(rigid_inverse(registration.transform), scan.points), o);
  r.registration = registration;
  return r;
}

std::string format_inspection(const InspectionReport& r, double tolerance) {
  std::ostringstream s;
  char line[256];
  const auto place = [&](const char* what, const Deviation& d) {
    std::snprintf(line, sizeof line, "%s: %+.4f mm at x %.3f y %.3f z %.3f\n", what, d.distance, d.place.x(),
                  d.place.y(), d.place.z());
    s << line;
  };
  const double n = double(std::max<size_t>(r.deviations.size(), 1));
  std::snprintf(line, sizeof line, "points: %zu\nmean deviation: %+.4f mm, rms %.4f mm\n", r.deviations.size(), r.mean,
                r.rms);
  s << line;
  place("largest excess", r.largest_excess);
  place("largest deficit", r.largest_deficit);
  std::snprintf(line, sizeof line, "within +-%.4g mm: %.2f%%, above: %.2f%%, below: %.2f%%\nhistogram (mm):\n",
                tolerance, 100 * double(r.within_tolerance) / n, 100 * double(r.above_tolerance) / n,
                100 * double(r.below_tolerance) / n);
  s << line;
  const size_t top = r.histogram.empty() ? 1 : std::max<size_t>(1, *std::max_element(r.histogram.begin(), r.histogram.end()));
  for (size_t b = 0; b < r.histogram.size(); ++b) {
    const double low = r.histogram_low + double(b) * r.bin_width;
    std::snprintf(line, sizeof line, "  %+9.4f .. %+9.4f %9zu %s\n", low, low + r.bin_width, r.histogram[b],
                  std::string(size_t(40.0 * double(r.histogram[b]) / double(top)), '#').c_str());
    s << line;
  }
  return s.str();
}

}  // namespace rosmill::core::scan
