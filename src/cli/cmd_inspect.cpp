// rosmill inspect DESIGN SCAN [--json] [--image map.png] [--stock-out stock.pcd] [--tolerance MM] [--registered]:
// the scan registered to the design (unless --registered: it is in the design's frame already), every point's
// signed distance to the design (+ excess material, - deficit), the histogram, the largest excess and deficit
// with their places. --stock-out writes the scan in the design's (workpiece) frame, the units of --scan-units,
// for a job's `stock: {cloud: FILE}`: the re-scan becomes the stock a rest job starts from.
#include <algorithm>
#include <iostream>

#include "command.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/scan/inspection.hpp"
#include "rosmill/verify/deviation_map.hpp"
#include "rosmill/verify/rgb_image.hpp"
#include "scan_inputs.hpp"

namespace rosmill::core::cli {
namespace {

struct InspectArgs : ScanInputs {
  std::string image, stock_out;
  double tolerance = 0.05;
  bool registered = false;
};

// The scan seen from above (+x right, +y up), each pixel in the colour band of its point furthest from the design
// (the verifier's bands: reds below the design, blues above), the legend beside it.
void write_image(const std::string& path, const scan::InspectionReport& r, double tolerance) {
  using namespace verify;
  Box3 box;
  for (const Vec3& p : r.points) box.add(p);
  const double extent = std::max({box.size().x(), box.size().y(), 1e-6});
  const int map = 600, legend = 260;
  const double scale = (map - 1) / extent;
  RgbImage image(map + legend, map, Rgb{255, 255, 255});
  std::vector<double> worst(size_t(map) * map, 0.0);
  std::vector<uint8_t> seen(size_t(map) * map, 0);
  for (size_t i = 0; i < r.points.size(); ++i) {
    const int x = int((r.points[i].x() - box.min.x()) * scale), y = map - 1 - int((r.points[i].y() - box.min.y()) * scale);
    const size_t k = size_t(y) * map + size_t(x);
    if (!seen[k] || std::abs(r.deviations[i]) > std::abs(worst[k])) worst[k] = r.deviations[i];
    seen[k] = 1;
  }
  const std::vector<DeviationBand> bands = deviation_bands(tolerance);
  for (int y = 0; y < map; ++y)
    for (int x = 0; x < map; ++x)
      if (seen[size_t(y) * map + size_t(x)])
        image.set(x, y, bands[deviation_band(worst[size_t(y) * map + size_t(x)], true, tolerance)].colour);
  for (size_t b = 0; b < bands.size(); ++b) {
    image.fill(map + 10, 10 + int(b) * 22, 16, 16, bands[b].colour);
    image.text(map + 32, 13 + int(b) * 22, bands[b].label, 1, Rgb{0, 0, 0});
  }
  write_png(path, image);
}

CommandRegistration reg([](CLI::App& app) {
  auto* cmd = app.add_subcommand("inspect", "compare a scan of the machined part with the design");
  auto a = std::make_shared<InspectArgs>();
  add_scan_inputs(cmd, *a);
  cmd->add_option("--tolerance", a->tolerance, "mm: deviations within +-this are in tolerance (0.05)");
  cmd->add_option("--image", a->image, "write the deviation map (seen from above) as a PNG picture");
  cmd->add_option("--stock-out", a->stock_out, "write the scan in the design's frame (PCD, --scan-units) as a stock");
  cmd->add_flag("--registered", a->registered, "the scan is in the design's frame already: no registration");
  cmd->callback([a] {
    scan::InspectionOptions o;
    o.tolerance = a->tolerance;
    o.registration = a->registration;
    const Mesh design = a->read_design();
    const PointCloud cloud = a->read_scan();
    const scan::InspectionReport r =
        a->registered ? scan::inspect_registered(design, cloud.points, o) : scan::inspect(design, cloud, o);
    if (!a->stock_out.empty()) {
      PointCloud stock;
      stock.points = r.points;
      write_cloud(a->stock_out, stock, parse_units(a->scan_units, "--scan-units"));
    }
    if (!a->image.empty()) write_image(a->image, r, a->tolerance);
    if (a->json) {
      std::cout << scan::inspection_json(r, a->tolerance, a->registered).dump() << std::endl;
      return;
    }
    if (!a->registered) std::cout << scan::format_registration(r.registration);
    std::cout << scan::format_inspection(r, a->tolerance);
  });
});

}  // namespace
}  // namespace rosmill::core::cli
