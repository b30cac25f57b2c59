// The generated benchmark part of the issues' tables: a closed solid whose top is a wavy height field.
// Shared by tests and benchmarks so that every figure quoted for "the 2M-triangle wavy solid" is the same part.
#pragma once
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

// Corners (3 per triangle, counter-clockwise from outside) of a block [0, length]^2 in XY whose top is
// z = 10 + 7.5 sin(10 pi i / n) cos(8 pi j / n) on an n x n grid (2 n^2 triangles), closed by one row of wall
// quads per rim segment (8 n triangles) and a bottom fan about the centre (4 n): 2 n^2 + 12 n triangles in all,
// 2,012,000 for n = 1000. Vertices shared between triangles are bit-identical, so an exact weld closes it.
std::vector<Vec3> wavy_solid_corners(int n = 1000, double length = 200.0);

}  // namespace rosmill::core
