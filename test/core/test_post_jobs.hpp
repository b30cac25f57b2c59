// Synthetic jobs for the G-code tests, shaped like the planners' output: a zig-zag raster over a box and
// z-level contours of the seed cylinder, cone and dome (the circles their sections make).
#pragma once
#include <cmath>

#include "rosmill/toolpath/job.hpp"

namespace rosmill::core::test {

// A move and a pass written out in a test.
inline Move move_to(MoveType type, const Vec3& to, double feed) {
  Move m;
  m.to = to;
  m.type = type;
  m.feed = feed;
  return m;
}

inline ToolpathPass pass_of(std::initializer_list<Move> moves) {
  ToolpathPass p;
  p.name = "pass";
  p.moves = moves;
  return p;
}

inline Tool test_tool(int id, double d) {
  Tool t;
  t.id = id;
  t.name = "test";
  t.cutter = Cutter::flat(d);
  t.spindle_rpm = 12000;
  t.feed = 800;
  t.plunge_feed = 200;
  return t;
}

inline Toolpath raster_toolpath(double w = 40, double h = 30, double step = 2.5, double z = -1.0, int tool = 1) {
  Toolpath tp;
  tp.strategy = "raster";
  tp.tool = test_tool(tool, 6);
  tp.safe_z = 5;
  tp.clearance_z = 10;
  tp.start = Vec3(0, 0, 10);
  ToolpathPass pass;
  pass.name = "raster";
  pass.moves.push_back({Vec3(0, 0, 5), MoveType::Rapid, 0});
  pass.moves.push_back({Vec3(0, 0, z), MoveType::Plunge, tp.tool.plunge_feed});
  bool forward = true;
  for (double y = 0; y <= h + 1e-9; y += step) {
    if (y > 0) pass.moves.push_back({Vec3(forward ? 0 : w, y, z), MoveType::Feed, tp.tool.feed});
    pass.moves.push_back({Vec3(forward ? w : 0, y, z), MoveType::Feed, tp.tool.feed});
    forward = !forward;
  }
  pass.moves.push_back({Vec3(pass.moves.back().to.x(), pass.moves.back().to.y(), 5), MoveType::Rapid, 0});
  tp.passes.push_back(pass);
  return tp;
}

// Contours of a solid of revolution (radius r(z)) offset outward by the tool radius, `segments` per circle,
// like the slicing planner's contours of the seed cylinder (r const), cone (r linear) and dome (r = sqrt).
template <class RadiusAt>
Toolpath revolution_contours(const std::string& name, RadiusAt radius_at, double z_top, double z_step, int segments,
                             int tool = 2) {
  Toolpath tp;
  tp.strategy = "contour:" + name;
  tp.tool = test_tool(tool, 6);
  tp.safe_z = z_top + 5;
  tp.clearance_z = z_top + 10;
  tp.start = Vec3(0, 0, tp.clearance_z);
  for (double z = z_top - z_step; z >= 0 - 1e-9; z -= z_step) {
    ToolpathPass pass;
    pass.name = "z " + std::to_string(z);
    const double r = radius_at(z) + tp.tool.cutter.radius();
    pass.moves.push_back({Vec3(r, 0, tp.safe_z), MoveType::Rapid, 0});
    pass.moves.push_back({Vec3(r, 0, z), MoveType::Plunge, tp.tool.plunge_feed});
    for (int s = 1; s <= segments; ++s) {
      const double a = 2 * M_PI * s / segments;
      pass.moves.push_back({Vec3(r * std::cos(a), r * std::sin(a), z), MoveType::Feed, tp.tool.feed});
    }
    pass.moves.push_back({Vec3(r, 0, tp.safe_z), MoveType::Rapid, 0});
    tp.passes.push_back(pass);
  }
  return tp;
}

inline Toolpath cylinder_contours() {
  return revolution_contours("cylinder", [](double) { return 25.0; }, 60, 5, 36);
}
inline Toolpath cone_contours() {
  return revolution_contours("cone", [](double z) { return 25.0 * (1 - z / 60.0); }, 60, 5, 36);
}
inline Toolpath dome_contours() {
  return revolution_contours("dome", [](double z) { return std::sqrt(std::max(0.0, 2500 - z * z)); }, 50, 2.5, 30);
}

}  // namespace rosmill::core::test
