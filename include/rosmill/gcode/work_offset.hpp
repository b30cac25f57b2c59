// Where the program's origin lies on the machine. The program sets it itself, before its first move, with
// RS274/NGC coordinate system data, `G10 L2 Pn X Y Z` (Kramer et al., "The NIST RS274NGC Interpreter - Version 3",
// section 3.5.5), and selects it (G54..G59 for P1..P6): a part registered on the table is machined where it sits
// (G54 at the workpiece frame's origin in machine coordinates), and each setup of a job has its own offset at its
// datum, so that the operator can tell the setups' zeros apart on the controller. LinuxCNC's G10 L2 also takes R, a rotation of the XY axes about
// Z (its G-code manual, "G10 L2 Set Coordinate System"); GRBL's takes no R. A tilt of the part out of the table's
// plane cannot be followed by a work offset on a 3-axis machine: it is refused, not rounded away.
#pragma once
#include <string>

#include <Eigen/Core>

#include "rosmill/gcode/dialect.hpp"
#include "rosmill/geometry/types.hpp"

namespace rosmill::core::gcode {

// The coordinate systems a program may set and select: P1..P6, G54..G59 (both LinuxCNC and GRBL have six).
constexpr int kWorkOffsets = 6;

struct WorkOffset {
  Vec3 origin = Vec3::Zero();  // mm: the coordinate system's origin in machine coordinates
  double rotation_deg = 0.0;   // of its X and Y axes about machine Z, counter-clockwise seen from +Z
  int index = 1;               // 1..6: G54..G59 (G10 L2 P<index>)

  std::string code() const;    // "G54".."G59"

  Vec3 to_machine(const Vec3& program) const;     // a program position in machine coordinates
  Vec3 to_program(const Vec3& machine) const;
  Eigen::Matrix4d pose() const;                   // machine <- program, mm
};

// The work offset of a workpiece pose (machine <- workpiece, mm, rigid): its translation and its turn about Z.
// Throws Error(where) when the pose is not rigid or tilts the workpiece's Z axis from the machine's by more than
// `max_tilt_deg`.
WorkOffset work_offset_of_pose(const Eigen::Matrix4d& pose, double max_tilt_deg, const std::string& where);

// The G10 L2 P<index> block that sets it, in the dialect's words; `decimals` as the program's lengths. Throws Error
// when the index is not 1..6, or the dialect has no coordinate system rotation and the offset turns by more than it
// can ignore (1e-4 degrees).
std::string work_offset_block(const WorkOffset& offset, const Dialect& dialect, int decimals);

// Reads "x,y,z[,rotation_deg]" (mm, degrees), as the CLI's --work-offset takes it; Error(where) on bad text.
WorkOffset parse_work_offset(const std::string& text, const std::string& where);

}  // namespace rosmill::core::gcode
