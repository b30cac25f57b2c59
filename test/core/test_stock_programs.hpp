// Programs and solids shared by the in-process stock's tests: single moves of a tool, a closed box mesh.
#pragma once
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/stock/program.hpp"

namespace stock_test {

using namespace rosmill::core;
using namespace rosmill::core::stock;

// A program of one tool from the moves given as (from, to, rapid); sources number the moves from `first_line`.
struct Step {
  Vec3 from, to;
  bool rapid = false;
};
inline MachineProgram program_of(const Cutter& cutter, const std::vector<Step>& steps, uint32_t first_line = 1) {
  MachineProgram p;
  p.tools.push_back(Tool{});
  p.tools.back().cutter = cutter;
  for (const Step& s : steps) {
    CanonMove m;
    m.from = s.from;
    m.to = s.to;
    m.rapid = s.rapid;
    m.feed = s.rapid ? 0.0f : 1000.0f;
    m.source = first_line++;
    p.moves.push_back(m);
  }
  return p;
}

// A closed box mesh, 12 triangles facing outwards (inwards when `inward`: a void inside another solid).
inline std::vector<Vec3> box_corners(const Vec3& lo, const Vec3& hi, bool inward = false) {
  auto c = [&](int i) { return Vec3(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z()); };
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<Vec3> corners;
  for (const auto& q : quads)
    for (const int t : {1, 2}) {
      corners.push_back(c(q[0]));
      corners.push_back(c(q[inward ? t + 1 : t]));
      corners.push_back(c(q[inward ? t : t + 1]));
    }
  return corners;
}

// The number of cells a closed outline of length `perimeter` can cross on a grid of `cell` mm, times the error
// each of them can make (its whole column of `height`): the bound on the dexel volume of a solid whose walls are
// vertical over that outline.
inline double outline_error(double perimeter, double height, double cell) {
  return (std::sqrt(2.0) * perimeter / cell + 4) * cell * cell * height;
}

}  // namespace stock_test
