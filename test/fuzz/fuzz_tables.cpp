// The configuration tables from their text: the tool table (config/tools.yaml), the planning presets
// (config/presets.yaml) and the machine's limits (config/machine.yaml). The first byte chooses the table, the
// rest is the file. Each is read or refused naming the file and the field.
#include "fuzz_support.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/planner/presets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rosmill;
  if (size == 0) return 0;
  const std::string text = fuzz::text_of(data + 1, size - 1);
  fuzz::read_or_refuse([&] {
    switch (data[0] % 3) {
      case 0: {
        const core::ToolTable table = core::parse_tool_table(text, "tools.yaml");
        for (const core::Tool& t : table.tools)
          fuzz::require(t.cutter.diameter > 0 && std::isfinite(t.cutter.diameter), "a tool without a diameter");
        break;
      }
      case 1: core::parse_presets(text, "presets.yaml"); break;
      default: {
        const core::gcode::MachineLimits m = core::gcode::parse_machine_limits(text, "machine.yaml");
        for (int a = 0; a < 3; ++a) fuzz::require(m.envelope.min[a] < m.envelope.max[a], "an empty envelope");
      }
    }
  });
  return 0;
}
