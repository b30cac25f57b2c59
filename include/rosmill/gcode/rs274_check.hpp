// Verification by LinuxCNC's own interpreter: `rs274 -g` (package linuxcnc-uspace) runs a program offline and
// prints the canonical machine moves it means. A program is right when rs274 accepts it and its moves are the
// toolpath's moves within the output precision.
#pragma once
#include <string>
#include <vector>

#include "rosmill/gcode/post.hpp"

namespace rosmill::gcode {

// One canonical move in program coordinates, in mm (rs274 prints the work offset and the tool length offset
// apart from the positions, and positions in the program's units: G20 programs are scaled here).
struct CanonMove {
  enum Kind { Traverse, Feed, Arc } kind = Traverse;
  Vec3 end = Vec3::Zero();
  Vec2 centre = Vec2::Zero();  // arcs (XY plane)
  int rotation = 0;            // arcs: -1 clockwise, +1 counter-clockwise
  double feed = 0.0;           // mm/min in force for Feed and Arc
  int canon_line = 0;          // line of rs274's output
};

struct Rs274Result {
  bool ok = false;
  int exit_status = -1;
  std::string error;             // rs274's message and the offending block when it refused the program
  size_t error_line = 0;         // 1-based program line of the offending block (0: not found)
  std::vector<CanonMove> moves;
  std::string plane_error;       // set when a move is not in the XY plane (only XY arcs are written)
};

// Runs `executable -t <table> -g <program> <out>` in a temporary folder; the tool table is made from the
// program's T words. Throws Error when rs274 cannot be started.
Rs274Result run_rs274(const std::vector<std::string>& program_lines, const std::string& executable = "rs274");
// Parses rs274's canonical output text.
std::vector<CanonMove> parse_canon(const std::string& text);

struct VerifyReport {
  bool ok = false;
  size_t canon_moves = 0;
  size_t toolpath_moves = 0;
  double max_deviation = 0.0;  // mm, between toolpath points and the canonical moves
  std::string problem;         // the first mismatch, naming the program line and the toolpath move
};

// Compares rs274's moves with the job the program was posted from: every canonical move's end is the toolpath
// move's point within the precision, moves are of the same kind with the same feed, points an arc replaced lie
// within `arc_tolerance` (+ precision) of it, and every toolpath move is carried out.
VerifyReport compare_with_job(const Program& program, const Job& job, const Rs274Result& rs274, double arc_tolerance);

}  // namespace rosmill::gcode
