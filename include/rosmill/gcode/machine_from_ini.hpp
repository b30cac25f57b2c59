// A machine file (machine_limits.hpp, config/machine.yaml) written from a LinuxCNC configuration: the envelope,
// the feeds and the trajectory planner's limits from the ini's [TRAJ], [AXIS_X..Z], [EMCMOT] and [DISPLAY], each
// number with the section and key it came from as a comment; what the ini does not say (the table, the spindle,
// rosmill's own clearances) is marked as such. Linear units mm or inch (converted to mm).
#pragma once
#include <string>

#include "rosmill/gcode/linuxcnc_ini.hpp"

namespace rosmill::core::gcode {

// Throws Error naming the file, the section and the key of a missing or invalid value.
std::string machine_yaml_from_ini(const LinuxcncIni& ini);

}  // namespace rosmill::core::gcode
