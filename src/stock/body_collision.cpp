#include "rosmill/stock/body_collision.hpp"

#include <cstdio>
#include <vector>

#include "rosmill/stock/material_removal.hpp"

namespace rosmill::core::stock {
namespace {

std::string point_text(const Vec3& p) {
  char s[96];
  std::snprintf(s, sizeof s, "(%.3f, %.3f, %.3f)", p.x() + 0.0, p.y() + 0.0, p.z() + 0.0);
  return s;
}

// The program with, after each move, the same move of every body of its tool that is wider than its cutter (lifted by
// its height above the tip, a flat end mill of its radius), so that each body meets the material as the cuts before
// it left it. `body_of[k]`: 0 for a move of the program, 1 for a shank's, 2 for a holder's; `index[k]` its move.
MachineProgram with_bodies(const MachineProgram& program, std::vector<uint8_t>& body_of, std::vector<size_t>& index) {
  MachineProgram out;
  out.tools = program.tools;
  const size_t n = program.tools.size();
  std::vector<double> lift(2 * n, -1);
  for (size_t t = 0; t < n; ++t) {
    const Tool& tool = program.tools[t];
    const double radius[2] = {0.5 * tool.cutter.shank_diameter, 0.5 * tool.holder_mm()};
    const double height[2] = {tool.cutter.flute_length, tool.stick_out_mm()};
    for (int b = 0; b < 2; ++b) {
      Tool body;
      body.cutter = Cutter::flat(2 * radius[b]);
      out.tools.push_back(body);
      if (radius[b] > tool.cutter.radius()) lift[b * n + t] = height[b];
    }
  }
  for (size_t k = 0; k < program.moves.size(); ++k) {
    const CanonMove& m = program.moves[k];
    out.moves.push_back(m);
    body_of.push_back(0);
    index.push_back(k);
    for (int b = 0; b < 2; ++b) {
      const double up = lift[b * n + m.tool];
      if (up < 0) continue;
      CanonMove lifted = m;
      lifted.from.z() += up;
      lifted.to.z() += up;
      lifted.tool = static_cast<uint16_t>(n + 2 * m.tool + b);
      out.moves.push_back(lifted);
      body_of.push_back(static_cast<uint8_t>(b + 1));
      index.push_back(k);
    }
  }
  return out;
}

}  // namespace

std::string BodyCollision::message() const {
  return "the " + body + " runs into the stock at move " + std::to_string(source) + " (from " + point_text(from) +
         " to " + point_text(to) + " mm)";
}

std::optional<BodyCollision> first_body_collision(const MachineProgram& program, const InProcessStock& stock,
                                                  const SetupFrame& setup) {
  if (program.moves.empty()) return std::nullopt;
  const Box3 material = stock.bounds_in(setup);
  if (material.empty()) return std::nullopt;
  std::vector<uint8_t> body_of;
  std::vector<size_t> index;
  const MachineProgram all = with_bodies(program, body_of, index);
  // Only a body that starts below the material's top can meet it.
  bool low = false;
  for (size_t k = 0; k < all.moves.size(); ++k)
    low |= body_of[k] && std::min(all.moves[k].from.z(), all.moves[k].to.z()) < material.max.z();
  if (!low) return std::nullopt;
  HeightField work = stock.view(setup);
  SimulationOptions o;
  o.trace_finishing = false;
  o.mark_cutting_moves = true;
  const SimulationResult r = simulate(all, work, o);
  for (size_t k = 0; k < all.moves.size(); ++k)
    if (body_of[k] && r.cutting_moves[k]) {
      const CanonMove& m = program.moves[index[k]];
      return BodyCollision{index[k], m.source, body_of[k] == 1 ? "shank" : "holder", m.from, m.to};
    }
  return std::nullopt;
}

}  // namespace rosmill::core::stock
