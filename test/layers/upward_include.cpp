// Compiled with the include paths of the gcode area only (see CMakeLists.txt, test area_include_enforced): the
// strategy table lies above G-code, so this include must not be found.
#include "rosmill/toolpath/toolpath.hpp"
#include "rosmill/planner/plan_request.hpp"
