// A canonical move: what a block asks the machine to do, in the terms of LinuxCNC's canonical machining
// functions (STRAIGHT_TRAVERSE, STRAIGHT_FEED, ARC_FEED; Kramer, Proctor and Messina, "The NIST RS274NGC
// Interpreter - Version 3", chapter 4). The G-code reader emits one per motion block; the machine-limits check,
// the resume preamble, the verifier, the stock's removal and the rs274 comparison all read this stream, and
// rs274's own output is read into it too. A toolpath type: the stock below the G-code layer sweeps it. Lengths in mm, program coordinates (the work offset's), feeds in mm/min.
#pragma once
#include <cstdint>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

enum class MoveShape : uint8_t { Line, ArcCW, ArcCCW };
// The arc plane (G17, G18, G19) and its two axes in ARC_FEED's order: XY, ZX, YZ; the third axis is the helix's.
enum class Plane : uint8_t { XY, ZX, YZ };

struct PlaneAxes {
  int first, second, normal;  // indices into x, y, z
};
PlaneAxes plane_axes(Plane plane);

struct CanonMove {
  Vec3 from = Vec3::Zero();
  Vec3 to = Vec3::Zero();
  Vec2 centre = Vec2::Zero();  // arcs: the centre in the plane's first and second axes (G17: x, y), absolute
  MoveShape shape = MoveShape::Line;
  bool rapid = false;          // G0 (STRAIGHT_TRAVERSE); feeds and arcs are not
  Plane plane = Plane::XY;     // arcs
  uint8_t turns = 1;           // arcs: P, the number of turns (1: the arc alone; each more adds a full circle)
  // The axes (bit 0 x, 1 y, 2 z) whose position the reader knows: a program does not say where the machine is
  // before it, so an axis is unknown until the program first gives it absolutely.
  uint8_t known_from = 7, known_to = 7;
  uint16_t tool = 0;           // the verifier's index of the tool in the spindle
  float feed = 0;              // mm/min in force for feeds and arcs (0 for rapids)
  uint32_t source = 0;         // the G-code line (1-based), a toolpath move number, or a line of rs274's output
  // The rotary axes A and C (degrees) at the move's start and end: the same for a cut of a 3+2 program, different
  // for an indexing move (which then moves no linear axis). `known_rotary`: bit 0 A, bit 1 C given absolutely.
  double a_from = 0, c_from = 0, a_to = 0, c_to = 0;
  uint8_t known_rotary = 0;
  // Under tool-centre-point kinematics (after M428 on a trunnion): X Y Z are the tool tip on the table and A, C turn
  // the tool axis along the move; else X Y Z are the machine's axes with the tool along +Z.
  bool tool_centre_point = false;

  bool is_arc() const { return shape != MoveShape::Line; }
  bool clockwise() const { return shape == MoveShape::ArcCW; }
  bool from_known() const { return known_from == 7; }
  bool to_known() const { return known_to == 7; }
  bool indexes() const { return a_from != a_to || c_from != c_to; }
};

}  // namespace rosmill::core
