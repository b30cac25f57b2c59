#include "rosmill/stock/program.hpp"

namespace rosmill::core::stock {

MachineProgram program_from_job(const std::vector<Toolpath>& job) {
  MachineProgram program;
  uint32_t number = 0;
  for (const Toolpath& tp : job) {
    program.tools.push_back(tp.tool);
    const uint16_t tool = static_cast<uint16_t>(program.tools.size() - 1);
    Vec3 at = tp.start;
    for (const ToolpathPass& pass : tp.passes) {
      for (const Move& mv : pass.moves) {
        ++number;
        CanonMove m;
        m.from = at;
        m.to = mv.to;
        m.rapid = mv.type == MoveType::Rapid;
        m.feed = m.rapid ? 0.0f : static_cast<float>(mv.feed);
        m.tool = tool;
        m.source = number;
        at = mv.to;
        program.moves.push_back(m);
      }
    }
    program.finishing_stepover = tp.tool.stepover;
  }
  return program;
}

bool is_toolpath_path(const std::string& path) {
  return path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

}  // namespace rosmill::core::stock
