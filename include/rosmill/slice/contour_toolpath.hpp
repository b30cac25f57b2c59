// Contour toolpaths from slices (seed 000's machining from its slices): at each layer the section is offset by
// the radius of a flat end mill, outwards around material and inwards in holes and pockets, so that the cutter
// touches the part without cutting into it. Offsetting is Clipper's (polyclipping 6.4.2) with round joins.
#pragma once
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/plan/strategy.hpp"
#include "rosmill/plan/toolpath.hpp"
#include "rosmill/slice/slicer.hpp"

namespace rosmill {

struct ContourOptions {
  double stepdown = 1.0;        // mm between layers, from Zmax - stepdown down to Zmin
  double allowance = 0.0;       // stock left on the walls (mm): the offset is radius + allowance
  double arc_tolerance = 0.001; // mm: largest gap between a round join's chords and its true arc
  bool climb = true;            // climb milling for a clockwise (M3) spindle; false: conventional
  double safe_clearance = 5.0;  // safe_z = Zmax + this
};

// A closed cutter-location loop in XY; `around_material` is true for a loop around material (counter-clockwise
// before the cutting direction is applied) and false for one inside a hole or pocket.
struct OffsetLoop {
  std::vector<Vec2> points;
  bool around_material = true;
};

// The loops at `distance` from the region bounded by the closed contours of `region` (outer counter-clockwise,
// holes clockwise; open chains are ignored: they bound no region). Loops come counter-clockwise around material
// and clockwise in holes.
std::vector<OffsetLoop> offset_region(const std::vector<Contour>& region, double distance, double arc_tolerance);

// The union of two regions given as closed contours (outer counter-clockwise, holes clockwise), as contours of the
// same kind. Used to carry the part above a layer down to it: a flat end mill's body must clear all of it.
std::vector<Contour> union_regions(const std::vector<Contour>& a, const std::vector<Contour>& b);

// One toolpath: a pass per layer, top to bottom; per loop a rapid at safe_z, a plunge, the loop at the feed and a
// retract. Throws Error for a cutter that is not a flat end mill or a non-positive stepdown.
Toolpath contour_toolpath(const Mesh& mesh, const Tool& tool, const ContourOptions& options,
                          const PlanProgress& progress = {});

// The "contour" strategy of the strategy table (PlanParams: tool, stepdown, allowance, tolerance, safe_clearance).
Job plan_contour(const PlanInput& input, const PlanParams& params, const PlanProgress& progress);

}  // namespace rosmill
