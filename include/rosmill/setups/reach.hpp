// What a tool reaches of a part along one tool direction (3-axis, the part turned so that the direction is +Z):
// the accessibility analysis behind setup selection (Lefebvre and Lauwers, "STL Model Segmentation for Multi-Axis
// Machining Operations Planning", section 3.3: several setups' segmentations coexist so that operations planning
// can choose among them). The part's surface is sampled (every piece of every facet stands for its area), and a
// sample counts as reached when
//   - it faces the tool: its normal within `max_angle_deg` of the direction (90: a wall parallel to the tool axis
//     is reached by the cutter's side);
//   - nothing of the part stands above it along the direction (a vertical line just off the surface is free);
//   - with the cutter touching it there (its contact point on the cutter's flank or corner: the axis offset from
//     the surface by the cutter's radius along the normal), the shank (from the flute length up) and the holder
//     (from the stick-out up, its diameter) stand clear of the part, and of the fixture when one is given.
// The cutter's own size is not held against a sample: a corner too tight for it is rest material for a smaller
// tool, not a reason to turn the part. Each test is the product's exact drop-cutter (plan/mesh_surface.hpp): "does
// anything within this radius of the axis stand above this height?", asked of the part turned into the setup.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/geometry/surface_samples.hpp"

namespace rosmill::core::setups {

// The surface's samples (geometry/surface_samples.hpp), as the setup choice has long named them.
using rosmill::core::sample_spacing;
using rosmill::core::sample_surface;
using rosmill::core::SurfaceSamples;

enum class Reach : uint8_t {
  Reached,
  FacesAway,  // its normal is beyond the largest angle from the tool direction
  Hidden,     // the part stands above it, or in the shank's or the holder's way
  Fixture,    // reached but for the fixture
};

struct ReachTool {
  double radius, corner_radius;  // mm, the cutter
  double flute_length, shank_radius, stick_out, holder_radius;
};
ReachTool reach_tool(const Tool& tool);

// Per sample, what the tool reaches along the setup's direction. `fixture`: triangles in the setup's frame (empty:
// none). Runs on both cores.
std::vector<Reach> reach_along(const Mesh& part, const SurfaceSamples& samples, const SetupFrame& setup,
                               const ReachTool& tool, const std::vector<Vec3>& fixture_corners,
                               double max_angle_deg = 90.0);

}  // namespace rosmill::core::setups
