// A machining program as the simulator sees it: straight lines and XY arcs of the tool tip, each with its tool
// and the place in the source that asked for it (a G-code line or a toolpath move number).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/types.hpp"
#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::verify {

enum class MoveShape : uint8_t { Line, ArcCW, ArcCCW };  // arcs lie in the XY plane (G17), z may change (helix)

struct SimMove {
  Vec3 from = Vec3::Zero();
  Vec3 to = Vec3::Zero();
  Vec2 centre = Vec2::Zero();  // arc centre in XY (arcs only)
  MoveShape shape = MoveShape::Line;
  bool rapid = false;          // G0: cutting material with it is a crash, the report counts it
  uint16_t tool = 0;           // index into MachineProgram::tools
  uint32_t source = 0;         // G-code line (1-based) or toolpath move number (1-based, over the whole job)
};

struct MachineProgram {
  std::vector<Tool> tools;
  std::vector<SimMove> moves;
  bool from_gcode = false;        // `source` is a G-code line (true) or a toolpath move number (false)
  double finishing_stepover = 0;  // stepover of the last tool's passes when known (toolpath files), else 0
};

// Our toolpath file's job: one toolpath per tool, in order. Each toolpath starts at its `start`.
MachineProgram program_from_job(const std::vector<Toolpath>& job);

// True when the file is a toolpath file (.json) rather than G-code.
bool is_toolpath_path(const std::string& path);

}  // namespace rosmill::verify
