// Four-axis finishing with a ball end mill: rings round the plan frame's Z axis, the tool axis at every cutter
// location in the plane across that axis (the surface normal's part in it, turned there by the lead towards travel),
// so that one rotary axis turning the part while it cuts follows the angle: on the trunnion, A at -90 degrees holds
// the part's axis level and C turns it (machine/trunnion.hpp). The contact is BallContact's (exact, shank and
// holder swept); a ring approaches and leaves along its first location's axis from the free space round the part,
// and rings are linked on the side of that space. The rotary axis is the plan frame's Z through x = y = 0: the
// program's origin on the C axis.
//
// The table the part stands on is not in the mesh: rings start a holder's radius above the part's bottom, so that
// the holder, coming in level, stays above the table.
#pragma once
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/plan/plan_params.hpp"
#include "rosmill/plan/plan_report.hpp"
#include "rosmill/toolpath/job.hpp"

namespace rosmill::core {

// Throws Error("four-axis", ...) for a cutter other than a ball end mill, an empty mesh, or when cancelled.
Job four_axis_finish(const Mesh& mesh, const PlanParams& params, const PlanProgress& progress,
                     PlanReport* report = nullptr);

}  // namespace rosmill::core
