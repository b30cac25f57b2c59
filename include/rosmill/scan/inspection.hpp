// Inspection of a machined part: its scan registered to the design, then every scan point's signed distance to
// the design's surface (+: material above the design, excess; -: below it, deficit), a histogram, the largest
// excess and deficit with their places, and the shares within and outside a tolerance.
#pragma once
#include <string>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/scan/design_registration.hpp"

namespace rosmill::core::scan {

struct InspectionOptions {
  double tolerance = 0.05;  // mm: |deviation| within this is in tolerance
  int bins = 20;            // histogram bins over [lowest, highest] deviation
  RegistrationOptions registration;
  void check() const;
};

struct Deviation {
  double distance = 0;          // mm, signed
  Vec3 place = Vec3::Zero();    // the scan point, in the design's frame (mm)
};

struct InspectionReport {
  RegistrationResult registration;  // identity when the scan came already in the design's frame
  std::vector<Vec3> points;         // the scan in the design's frame
  std::vector<double> deviations;   // per point, signed (mm)
  Deviation largest_excess, largest_deficit;
  double mean = 0, rms = 0;
  size_t within_tolerance = 0, above_tolerance = 0, below_tolerance = 0;
  double histogram_low = 0, bin_width = 0;
  std::vector<size_t> histogram;
};

// Registers the scan to the design (refusing as register_design does), then measures.
InspectionReport inspect(const Mesh& design, const PointCloud& scan, const InspectionOptions& options = {});
// Measures a scan already in the design's frame.
InspectionReport inspect_registered(const Mesh& design, const std::vector<Vec3>& points,
                                    const InspectionOptions& options = {});

// The report as text: the summary, the histogram as rows of bars.
std::string format_inspection(const InspectionReport& r, double tolerance);

}  // namespace rosmill::core::scan
