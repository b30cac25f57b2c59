// rosmill register DESIGN.stl SCAN.(pcd|ply) [--units U] [--scan-units U] [--json] [thresholds]: the rigid
// transform that maps the design onto the scan (4x4, row-major, mm), its fitness, and whether the pose is
// ambiguous; a refusal exits non-zero with the reason.
#include <iostream>

#include "command.hpp"
#include "scan_inputs.hpp"

namespace rosmill::core::cli {
namespace {

CommandRegistration reg([](CLI::App& app) {
  auto* cmd = app.add_subcommand("register", "locate the design in a scan of the part (no initial guess needed)");
  auto a = std::make_shared<ScanInputs>();
  add_scan_inputs(cmd, *a);
  cmd->callback([a] {
    const scan::RegistrationResult r = scan::register_design(a->read_design(), a->read_scan(), a->registration);
    if (a->json)
      std::cout << registration_json(r).dump() << std::endl;
    else
      std::cout << scan::format_registration(r);
  });
});

}  // namespace
}  // namespace rosmill::core::cli
