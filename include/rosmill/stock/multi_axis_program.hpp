// A multi-axis program as the stock removes it: straight moves of the tool tip (workpiece frame, mm), each with the
// tool axis at its start and its end (unit, from the tip towards the spindle), as tool-centre-point control runs
// them: the tip straight along the move, the axis turning in proportion (LinuxCNC's xyzac-trt kinematics under
// M428 interpolates the program's X Y Z and A C together).
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/types.hpp"
#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::core::stock {

struct AxisMove {
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();
  Vec3 axis_from = Vec3::UnitZ(), axis_to = Vec3::UnitZ();
  uint16_t tool = 0;    // index in MultiAxisProgram::tools
  bool rapid = false;   // a rapid that cuts material is a collision
  uint32_t source = 0;  // a toolpath move number over the whole job (1-based), or a G-code line
};

struct MultiAxisProgram {
  std::vector<Tool> tools;
  std::vector<AxisMove> moves;
};

// Our toolpaths, one per tool, in order: each starts at its `start` with the axis of its first move (the post turns
// the table to it before the tool comes down); a pass without axes keeps the frame's +Z.
MultiAxisProgram multi_axis_program_from_job(const std::vector<Toolpath>& job);

}  // namespace rosmill::core::stock
