// Contour toolpaths from slices (the machining from slices of "Tool Path Generation for CNC Milling based on STL
// Files"): at each layer the section is offset by
// the radius of a flat end mill, outwards around material and inwards in holes and pockets, so that the cutter
// touches the part without cutting into it. Offsetting: geometry/polygon_offset.hpp.
#pragma once
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/polygon_offset.hpp"
#include "rosmill/plan/plan_params.hpp"
#include "rosmill/toolpath/job.hpp"
#include "rosmill/slice/slicer.hpp"

namespace rosmill::core {

struct ContourOptions {
  double stepdown = 1.0;        // mm between layers, from Zmax - stepdown down to Zmin
  double allowance = 0.0;       // stock left on the walls (mm): the offset is radius + allowance
  double arc_tolerance = 0.001; // mm: largest gap between a round join's chords and its true arc
  bool climb = true;            // climb milling for a clockwise (M3) spindle; false: conventional
  double safe_clearance = 5.0;  // safe_z = Zmax + this
};

// One toolpath: a pass per layer, top to bottom; per loop a rapid at safe_z, a plunge, the loop at the feed and a
// retract. Throws Error for a cutter that is not a flat end mill or a non-positive stepdown.
Toolpath contour_toolpath(const Mesh& mesh, const Tool& tool, const ContourOptions& options,
                          const PlanProgress& progress = {});

// The "contour" strategy of the strategy table (PlanParams: tool, stepdown, allowance, tolerance, safe_clearance).
Job plan_contour(const Mesh& mesh, const PlanParams& params, const PlanProgress& progress);

}  // namespace rosmill::core
