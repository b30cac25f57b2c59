// rosmill machine --from-ini FILE.ini [-o MACHINE.yaml]
// Writes a machine file (config/machine.yaml's format) from a LinuxCNC configuration: its envelope, feeds and the
// trajectory planner's limits that time every program, each number with the ini section and key it came from. The
// file is read back as a machine file before it is printed or written, so what leaves is what rosmill loads.
#include <cstdio>
#include <fstream>
#include <memory>

#include "command.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/linuxcnc_ini.hpp"
#include "rosmill/gcode/machine_from_ini.hpp"
#include "rosmill/gcode/machine_limits.hpp"

namespace rosmill::core::cli {
namespace {

struct MachineArgs {
  std::string ini, out;
};

void run(const MachineArgs& a) {
  const std::string yaml = gcode::machine_yaml_from_ini(gcode::LinuxcncIni::read(a.ini));
  gcode::parse_machine_limits(yaml, a.out.empty() ? "the machine file from " + a.ini : a.out);
  if (a.out.empty()) {
    std::printf("%s", yaml.c_str());
    return;
  }
  std::ofstream out(a.out);
  if (!(out << yaml) || !out.flush()) throw Error(a.out, "cannot write the machine file");
}

CommandRegistration reg([](CLI::App& app) {
  auto a = std::make_shared<MachineArgs>();
  auto* cmd = app.add_subcommand("machine", "write a machine file (config/machine.yaml) from a LinuxCNC ini file");
  cmd->add_option("--from-ini", a->ini, "the LinuxCNC configuration (e.g. sim/axis/axis_mm.ini)")->required();
  cmd->add_option("-o", a->out, "write the machine file here instead of printing it");
  cmd->callback([a] { run(*a); });
});

}  // namespace
}  // namespace rosmill::core::cli
