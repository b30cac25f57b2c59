// The post-processor: a job (one toolpath per tool) becomes an RS274/NGC program in a controller's dialect.
//
// Positions are written in millimetres in the work offset (G54) with fixed precision (`decimals`); a word is
// written only when it changes (modal motion, feed and axis words); numbers never read "-0". Every line keeps
// where it came from (toolpath, pass, moves) so a controller's line number leads back to the toolpath.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "rosmill/gcode/dialect.hpp"
#include "rosmill/gcode/work_offset.hpp"
#include "rosmill/machine/trunnion.hpp"
#include "rosmill/toolpath/job.hpp"

namespace rosmill::core::gcode {

enum class Coolant { Off, Flood, Mist };

struct PostOptions {
  std::string dialect = "linuxcnc";
  // Digits after the point for lengths (feeds and speeds use fewer); 0: chosen from the toolpaths' tolerance
  // (decimals_for_tolerance), 3 when they state none.
  int decimals = 0;
  double blend_tolerance = 0.01;   // G64 P (mm) where the dialect blends paths
  bool line_numbers = false;       // N words
  int line_number_step = 10;
  bool arcs = false;               // fit G2/G3 arcs to runs of feed moves (see arc_fit.hpp)
  double arc_tolerance = 0.005;    // mm: the arc stays this close to the polyline it replaces
  Coolant coolant = Coolant::Flood;
  std::string title;               // written as a comment in the header
  // Set and selected by the program before its first move (G10 L2 Pn, then G54..G59; see work_offset.hpp): where
  // the part was found on the table, or a setup's datum. Without it the controller's G54 is used as it stands.
  std::optional<WorkOffset> work_offset;
  std::string work_offset_note = "from the workpiece's pose on the table";  // the comment above the G10 block
  // Indexed toolpaths (a trunnion table): the machine Z (G53) the tool retracts to before the part turns.
  double index_safe_z = NAN;
  // Indexed toolpaths on a trunnion that also runs tool-centre-point programs: the program selects identity
  // kinematics (LinuxCNC's M429 on the xyzac-trt configuration) before its first turn, whatever the program before
  // it left the machine in.
  bool select_identity = false;
  // Multi-axis toolpaths (a tool axis per move): the trunnion with tool-centre-point control they are written for. The
  // program retracts and turns the table in identity kinematics, switches to tool-centre-point kinematics (LinuxCNC's
  // M428 on the xyzac-trt configuration), and writes the tip on the table with A and C at every move
  // (machine/trunnion.hpp indexes_along: the least rotary motion, C's winding kept); M429 at its end.
  std::optional<machine::Trunnion> trunnion;
  // Multi-axis moves are written in inverse time (G93): each takes the longest of its tip's length at its feed, and
  // its program axes' and the machine's joints' travel at these speeds (mm/s of X, Y, Z; the trunnion's own for A
  // and C; 0: not limited). LinuxCNC limits the program's axes but not the joints that a turning table drives.
  Vec3 axis_velocity = Vec3::Zero();
  double max_feed = 0;  // mm/min the tip moves at most, a rapid's too (0: not limited)
  // Where G54's origin sits on the machine when the program does not set it (`work_offset` empty): the machine
  // file's, for the joints' travel.
  Vec3 program_origin = Vec3::Zero();
};

// Where a program line came from: toolpath index, pass index and the moves [first_move, last_move] it carries
// out (-1 for lines that are not moves of the toolpath: header, tool change, retracts, end).
struct LineOrigin {
  int toolpath = -1;
  int pass = -1;
  int first_move = -1;
  int last_move = -1;
};

struct Program {
  std::vector<std::string> lines;   // without line ends
  std::vector<LineOrigin> origin;   // one per line
  std::string dialect;
  int decimals = 3;

  std::string text() const;         // lines joined with '\n', ending with '\n'
  size_t motion_blocks() const;     // lines that move the machine (G0/G1/G2/G3 blocks)
};

// The fewest decimals (3 to 6) whose rounding moves a point by at most a tenth of `tolerance`: half a unit of the
// last digit on each of three axes, sqrt(3)/2 * 10^-d <= tolerance / 10. The default plan tolerance, 0.001 mm,
// takes 4 decimals (a point moves at most 0.000087 mm); 0.01 mm takes 3.
int decimals_for_tolerance(double tolerance);

// The default options with another dialect.
PostOptions post_options_for(const std::string& dialect);

Program post(const Job& job, const PostOptions& options = {});

// The program's lines that switch the trunnion's kinematics (M428 to tool-centre-point, M429 back to identity):
// remaps of LinuxCNC's configuration, which its standalone interpreter cannot run (it stops at them).
bool switches_kinematics(const std::string& line);

// The block that turns a trunnion's table to A and C (degrees) as the post writes it: "G0 A-90 C180".
std::string index_block(double a, double c);

void write_program(const std::string& path, const Program& program);
// Writes lines, each ended by '\n'; throws Error naming the file.
void write_program_lines(const std::string& path, const std::vector<std::string>& lines);
// True when the file name ends in .ngc, .nc or .gcode (any case): what `rosmill plan -o` writes as G-code.
bool is_program_path(const std::string& path);
// Reads a program file into lines (no line ends); throws Error naming the file.
std::vector<std::string> read_program_lines(const std::string& path);

}  // namespace rosmill::core::gcode
