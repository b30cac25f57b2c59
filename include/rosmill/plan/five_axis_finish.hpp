// Five-axis finishing with a ball end mill: raster lines over the part seen from +Z, each cutter location with its
// own tool axis (plan/tool_axis.hpp: the smooth surface normal turned by lead and tilt, inside a cone about +Z,
// turned along a pass no faster than a rate). The ball is pushed along that axis onto the mesh (an exact contact,
// geometry/sphere_sweep.hpp), so the ball and a shank as wide are clear of the part all the way up the axis; the
// holder is swept the same way. Where the rule's axis is blocked (an overhang, a wall), the axis is turned, as
// little as the cone allows, to one that reaches the surface; where none does, the pass breaks and the point is
// counted. Approach and retract run along the tool axis, through the space the sweep found free.
//
// The toolpath's moves are tool-tip positions in the plan's frame, with the axis at each (ToolpathPass::axes):
// a machine with tool-centre-point control turns them into its joints (machine/trunnion.hpp).
#pragma once
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/plan/plan_params.hpp"
#include "rosmill/plan/plan_report.hpp"
#include "rosmill/toolpath/job.hpp"

namespace rosmill::core {

// Throws Error("five-axis", ...) for a cutter other than a ball end mill, an empty mesh, or when cancelled.
Job five_axis_finish(const Mesh& mesh, const PlanParams& params, const PlanProgress& progress,
                     PlanReport* report = nullptr);

}  // namespace rosmill::core
