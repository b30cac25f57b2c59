// Programs and stocks shared by the verifier's tests: the cube's top faced with a flat end mill (G-code), a
// ball raster over a flat floor (a toolpath), a box of stock.
#pragma once
#include <cmath>
#include <sstream>
#include <string>

#include "rosmill/toolpath/toolpath.hpp"
#include "rosmill/verify/verify.hpp"

namespace verify_test {

using namespace rosmill::core;
using namespace rosmill::core::verify;
using namespace rosmill::core::stock;

inline StockSpec box(double x0, double y0, double z0, double x1, double y1, double z1) {
  StockSpec s;
  s.kind = StockSpec::Kind::Box;
  s.box.add(Vec3(x0, y0, z0));
  s.box.add(Vec3(x1, y1, z1));
  return s;
}

// Facing of the cube's top at z 60 with a 10 mm flat end (T1), lines along x every 5 mm (one G-code line each).
inline std::string facing() {
  std::ostringstream g;
  g << "G21 G90 G17 (facing)\nT1 M6\nG0 X-6 Y0 Z70\nG1 Z60 F500\n";
  for (int k = 0; k <= 12; ++k) g << "G1 Y" << 5 * k << "\nG1 X" << (k % 2 ? -6 : 66) << "\n";
  g << "G0 Z70\n";
  return g.str();
}

// Lines of a program text.
inline int lines_of(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

// Raster finishing of a flat floor (the top of a 20 mm cube at z 20) with a ball: lines along x every `s` mm.
inline Toolpath flat_raster(double D, double s) {
  Toolpath tp;
  tp.strategy = "raster";
  tp.tool.cutter = Cutter::ball(D);
  tp.tool.stepover = s;
  tp.start = Vec3(-5, 0, 30);
  ToolpathPass pass;
  pass.moves.push_back({Vec3(-5, 0, 20), MoveType::Plunge, 300});
  const int n = static_cast<int>(std::round(20 / s));
  for (int k = 0; k <= n; ++k) {
    const double x_end = k % 2 ? -5 : 25;
    pass.moves.push_back({Vec3(x_end, k * s, 20), MoveType::Feed, 1000});
    if (k < n) pass.moves.push_back({Vec3(x_end, (k + 1) * s, 20), MoveType::Feed, 1000});
  }
  pass.moves.push_back({Vec3(25, 20, 30), MoveType::Rapid, 0});
  tp.passes.push_back(pass);
  return tp;
}

}  // namespace verify_test
