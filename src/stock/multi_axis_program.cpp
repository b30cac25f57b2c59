#include "rosmill/stock/multi_axis_program.hpp"

namespace rosmill::core::stock {
namespace {

// The axis a toolpath starts with: its first multi-axis move's, else +Z.
Vec3 first_axis(const Toolpath& tp) {
  for (const ToolpathPass& pass : tp.passes)
    if (!pass.moves.empty()) return pass.axes.empty() ? Vec3::UnitZ() : pass.axes.front();
  return Vec3::UnitZ();
}

}  // namespace

MultiAxisProgram multi_axis_program_from_job(const std::vector<Toolpath>& job) {
  MultiAxisProgram program;
  uint32_t number = 0;
  for (const Toolpath& tp : job) {
    program.tools.push_back(tp.tool);
    const uint16_t tool = static_cast<uint16_t>(program.tools.size() - 1);
    Vec3 at = tp.start, axis = first_axis(tp);
    for (const ToolpathPass& pass : tp.passes)
      for (size_t k = 0; k < pass.moves.size(); ++k) {
        AxisMove m;
        m.from = at;
        m.to = pass.moves[k].to;
        m.axis_from = axis;
        m.axis_to = k < pass.axes.size() ? pass.axes[k] : Vec3::UnitZ();
        m.tool = tool;
        m.rapid = pass.moves[k].type == MoveType::Rapid;
        m.source = ++number;
        at = m.to;
        axis = m.axis_to;
        program.moves.push_back(m);
      }
  }
  return program;
}

}  // namespace rosmill::core::stock
