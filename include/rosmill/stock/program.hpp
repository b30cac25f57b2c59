// A machining program as the simulator sees it: straight lines and XY arcs of the tool tip, each with its tool
// and the place in the source that asked for it (a G-code line or a toolpath move number).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/types.hpp"
#include "rosmill/toolpath/canon_move.hpp"
#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::core::stock {

// The simulator's moves are canonical moves (toolpath/canon_move.hpp: arcs in the XY plane, z may change: a
// helix); `tool` indexes MachineProgram::tools, `source` is a G-code line or a toolpath move number (1-based, over
// the whole job).
struct MachineProgram {
  std::vector<Tool> tools;
  std::vector<CanonMove> moves;
  bool from_gcode = false;        // `source` is a G-code line (true) or a toolpath move number (false)
  double finishing_stepover = 0;  // stepover of the last tool's passes when known (toolpath files), else 0
};

// Our toolpath file's job: one toolpath per tool, in order. Each toolpath starts at its `start`.
MachineProgram program_from_job(const std::vector<Toolpath>& job);

// True when the file is a toolpath file (.json) rather than G-code.
bool is_toolpath_path(const std::string& path);

}  // namespace rosmill::core::stock
