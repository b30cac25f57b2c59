// rosmill inspect DESIGN SCAN [--json] [--image map.png] [--stock-out stock.pcd] [--tolerance MM] [--registered]:
// the scan registered to the design (unless --registered: it is in the design's frame already), every point's
// signed distance to the design (+ excess material, - deficit), the histogram, the largest excess and deficit
// with their places. --stock-out writes the scan in the design's (workpiece) frame, the units of --scan-units,
// for a job's `stock: {cloud: FILE}`: the re-scan becomes the stock a rest job starts from.
#include <filesystem>
#include <iostream>

#include "command.hpp"
#include "rosmill/geometry/outline_from_above.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/scan/inspection.hpp"
#include "rosmill/verify/inspection_image.hpp"
#include "scan_inputs.hpp"

namespace rosmill::core::cli {
namespace {

struct InspectArgs : ScanInputs {
  std::string image, stock_out;
  double tolerance = 0.05;
  bool registered = false;
};

// The map's title names the design, the scan and today.
picture::MapCaption caption(const InspectArgs& a) {
  return {"inspection map", std::filesystem::path(a.design).filename().string(),
          "scan " + std::filesystem::path(a.scan).filename().string(), ""};
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
    if (!a->image.empty())
      verify::write_inspection_png(a->image, r, a->tolerance, outline_from_above(design), caption(*a));
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
