// Verification by LinuxCNC's own interpreter: `rs274 -g` (package linuxcnc-uspace) runs a program offline and
// prints the canonical machine moves it means. A program is right when rs274 accepts it and its moves are the
// toolpath's moves within the output precision.
#pragma once
#include <string>
#include <vector>

#include "rosmill/toolpath/canon_move.hpp"
#include "rosmill/gcode/post.hpp"

namespace rosmill::core::gcode {

struct Rs274Result {
  bool ok = false;
  int exit_status = -1;
  std::string error;             // rs274's message and the offending block when it refused the program
  size_t error_line = 0;         // 1-based program line of the offending block (0: not found)
  std::vector<CanonMove> moves;  // in mm (rs274 prints the program's units: G20 programs are scaled here), program
                                 // coordinates (rs274 prints the work and tool length offsets apart); `source`
                                 // is the line of rs274's output
};

// Runs `executable -t <table> -g <program> <out>` in a temporary folder; the tool table is made from the
// program's T words, and the trunnion's kinematics switches (M428, M429: post.hpp switches_kinematics) are read as
// comments. Throws Error when rs274 cannot be started.
Rs274Result run_rs274(const std::vector<std::string>& program_lines, const std::string& executable = "rs274");
// Parses rs274's canonical output text into canonical moves, each starting where the one before ended.
std::vector<CanonMove> parse_canon(const std::string& text);

struct VerifyReport {
  bool ok = false;
  size_t canon_moves = 0;
  size_t toolpath_moves = 0;
  double max_deviation = 0.0;  // mm, between toolpath points and the canonical moves
  std::string problem;         // the first mismatch, naming the program line and the toolpath move
};

// Compares rs274's moves with the job the program was posted from, through the program's own canonical moves (the
// reader's; one per motion line, as rs274 makes them): every canonical move's end is the toolpath
// move's point within the precision, moves are of the same kind with the same feed, points an arc replaced lie
// within `arc_tolerance` (+ precision) of it, and every toolpath move is carried out.
VerifyReport compare_with_job(const Program& program, const Job& job, const Rs274Result& rs274, double arc_tolerance);

}  // namespace rosmill::core::gcode
