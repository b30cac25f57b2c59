// The tilted tool of a multi-axis toolpath against the design, by a method that shares no code with the planner's
// contact (plan/ball_contact.hpp): the exact distance from points to the mesh of scan/mesh_distance.hpp (a k-d tree
// over the facets, the closest point on each near one), which planning does not use. The ball is checked by its
// centre's distance; the flutes, shank and holder by points along the axis every `step` mm, each at least its radius
// from the mesh, which leaves a cylinder of radius r up to r - sqrt(r^2 - step^2 / 4) deeper between two points
// (stated in the result). Each move's end and middle, the tip and the axis as the controller interpolates them.
#pragma once
#include <cstddef>
#include <string>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/toolpath/job.hpp"

namespace rosmill::core::verify {

struct ToolClearance {
  double ball_depth_mm = 0;  // the most the ball (grown by the allowance) goes into the design
  double body_depth_mm = 0;  // the most the flutes, shank or holder do (sampled)
  double sampling_mm = 0;    // what the sampling of the body may miss on top of that
  size_t positions = 0;      // tool positions checked
  std::string deepest;       // where the deepest is: "toolpath T, pass P, move M"
};

// Every multi-axis toolpath of the job against `design` (the plan's frame and units), with the stock `allowance`
// the toolpaths were planned to leave. Toolpaths without a tool axis per move are skipped.
ToolClearance check_tool_clearance(const Mesh& design, const Job& job, double allowance, double step = 0.25);

}  // namespace rosmill::core::verify
