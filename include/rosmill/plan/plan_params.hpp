// What every planning strategy is given besides the surface: the tool, stepover, step-down, allowance,
// tolerance and heights, and the progress callback through which a long plan reports and is cancelled.
#pragma once
#include <cmath>
#include <functional>
#include <string>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/plan/material_top.hpp"

namespace rosmill::core {

// How a line is sampled into cutter locations (raster.hpp): chord refinement to the tolerance, or the step-error
// interpolation with the swept-move check of Muslimin et al., "Direct NC Toolpath Generation from 3D Point Cloud
// Datasets" (step_error.hpp).
enum class Sampling { Chord, StepError };
const char* sampling_name(Sampling s);
// "chord" or "step-error"; throws Error naming `where` otherwise.
Sampling parse_sampling(const std::string& text, const std::string& where);

// The chord / gouge tolerance (mm) a plan keeps when none is given.
constexpr double kDefaultTolerance = 0.001;

// The tool axis of multi-axis finishing (plan/tool_axis.hpp), in degrees. The lead tilts the axis from the surface
// normal towards the direction of travel, the tilt sideways (to the right of travel): a ball end mill then cuts off
// its tip, where the cutting speed is zero. The cone bounds the axis around the setup's +Z (the machine's rotary
// range), the rate how fast it may turn along a pass.
struct ToolAxisParams {
  double lead_deg = NAN;  // NaN: 10 for a ball end mill (Muslimin et al.: off the zero-speed tip), 0 else
  double tilt_deg = 0.0;
  double cone_deg = 60.0;        // largest angle between the tool axis and +Z
  double rate_deg_per_mm = 5.0;  // largest change of the axis per mm of travel along a pass
  double lead_or_default(bool ball) const { return std::isnan(lead_deg) ? (ball ? 10.0 : 0.0) : lead_deg; }
};

// Parameters; NaN means "the tool's default" (stepover, stepdown) or the strategy's default.
struct PlanParams {
  Tool tool;
  double stepover = NAN;
  double stepdown = NAN;
  double allowance = 0.0;    // stock to leave on every surface (mm)
  double tolerance = kDefaultTolerance;  // chord / gouge tolerance (mm)
  double angle_deg = 0.0;    // raster direction in the XY plane
  double stock_margin = 5.0; // box stock: the part's bounding box grown by this (mm)
  // Roughing from a stock mesh instead of the box (closed, containing the part, same frame and units; not owned;
  // see plan/stock.hpp). Its bounding box then gives the levels' top and the safe height.
  const Mesh* stock_mesh = nullptr;
  double safe_clearance = 5.0; // safe_z above the stock top (mm)
  // The material as a job's stock left it (material_top.hpp; not owned; null: the box or the stock mesh). Roughing
  // then starts at its top, cuts only where it has material and links over it at link_clearance instead of at the
  // safe height; with rest cells every strategy's moves are kept to where rest material is (rest_moves.hpp).
  const MaterialTop* material = nullptr;
  double link_clearance = 2.0; // mm a link over the material keeps above it
  // mm over the material under the cutter where the rapid down into a cut over a job's material stops (the rest
  // at the plunge feed): the feed plane of CAM systems.
  double approach = 0.5;
  double air_gap = NAN;        // longest feed through air roughing bridges between two cuts (mm); NaN: the diameter
  Sampling sampling = Sampling::Chord;
  // Adaptive clearing: the largest radial engagement of the cutter, degrees (0, 180]; NaN: the engagement of a
  // straight side cut one stepover wide, acos(1 - stepover / R).
  double engagement_deg = NAN;
  // mm/min the machine feeds at most (0: no cap): a feed raised for a thin engagement stops there.
  double max_feed = 0.0;
  ToolAxisParams tool_axis;  // five-axis finishing
};

// Throws Error naming the field ("parameter allowance") and its accepted range when a value is NaN where NaN does
// not mean a default, infinite or out of range: the tool (check_tool), stepover and step-down (NaN or (0, 500] mm),
// allowance [0, 50] mm, tolerance (NaN or [1e-6, 10] mm), angle [-360, 360] degrees, stock margin [0, 1000] mm, safe
// clearance (0, 1000] mm, the tool axis's lead and tilt [-45, 45] degrees, its cone [0, 90] degrees and rate
// (0, 180] degrees per mm. plan() checks every request here, whoever sends it (the command line, a node).
void check_plan_params(const PlanParams& params);

// Progress in [0, 1]; return false to cancel (the strategy then throws Error("plan", "cancelled")).
using PlanProgress = std::function<bool(double fraction)>;

}  // namespace rosmill::core
