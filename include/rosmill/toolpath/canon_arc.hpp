// XY arcs of canonical moves (G2/G3 in G17, helical z): angles, points and bounds shared by the simulator, the
// machine-limits check and their tests.
#pragma once
#include "rosmill/toolpath/canon_move.hpp"

namespace rosmill::core {

// Signed sweep angle of an arc move in radians: positive counter-clockwise (G3), negative clockwise (G2); a move
// that ends where it starts in XY is a full turn (±2π).
double arc_sweep(const CanonMove& arc);
// The point at fraction s in [0, 1] along the move (lines and arcs; z changes linearly along the arc).
Vec3 move_point(const CanonMove& move, double s);
// Length of the move's path in mm (a helix: its turns' XY length and its z change together).
double move_length(const CanonMove& move);
// XY bounds of the move's axis path (the arc's extreme points included).
void move_xy_bounds(const CanonMove& move, Vec2& min, Vec2& max);

}  // namespace rosmill::core
