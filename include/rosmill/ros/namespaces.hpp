// The two sides the ROS layer joins: the core (namespace rosmill::core, no ROS) and the messages, services and
// actions catkin generates (namespace rosmill, written msg:: here). A name both have (Toolpath, Tool, Contour,
// Patch, SliceLayer, ToolpathPass) must be written core:: or msg::; every other core name is visible as it is.
#pragma once

namespace rosmill::core {}

namespace rosmill::edge {
namespace msg = ::rosmill;
using namespace ::rosmill::core;
}  // namespace rosmill::edge
