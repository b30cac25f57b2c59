// Adaptive clearing: z-level roughing at a bounded radial engagement of the cutter. At each level (the step-downs
// and every flat face plus the allowance, levels.hpp) the region to clear is the material standing above the level
// (the job's in-process stock, a stock mesh's section or the stock box) within reach of the cutter, which keeps
// out of the part grown by the allowance (the waterline's cutter-location loops at that level, waterline.hpp).
//
// The cleared area grows in rings, as in contour-parallel pocketing from the inside out (Held, "On the
// Computational Geometry of Pocket Machining", 1991) but each ring is chosen by its engagement: the cutter's centre
// runs on the boundary of the cleared area shrunk by R - s (Clipper offsets), smoothed by an opening and a closing
// of the smallest turn radius, and kept to where it meets material; s starts at the step of a straight side cut at
// the engagement limit and is cut down until every point of the ring keeps the cutter's leading half-circle in
// material for at most the limit (measured against the material left, level_material.hpp). So the engagement stays
// bounded around the curved fronts near an entry and into inner corners, where fixed-stepover offsets bury the tool.
// Rings run climb milling (material on the cutter's right for an M3 spindle).
//
// A ring's piece is entered from cleared air: straight along the level where the cutter's disc meets no material
// and stays out of the part, else by an arc lead-in tangent to it, from above over the material on the way. Where
// no cleared air is in reach (a closed pocket, the first level) the cutter enters by a helix at the deepest point
// of the material left, or by a ramp along the longest straight way where no helix fits (a slot barely wider than
// the tool), starting just above the material there. Feeds follow the engagement of each move.
#pragma once
#include "rosmill/plan/plan_report.hpp"
#include "rosmill/plan/plan_support.hpp"

namespace rosmill::core {

// The most the radial engagement of a move at a level passes the limit by, as the verifier measures it
// (verify/engagement.hpp, within its own tolerance besides): the planner samples its rings every R/20 on a bitmap of
// R/20 cells (2 degrees), and a ring that turns into an inner corner tighter than its turn radius takes up to
// about 8 degrees more there (measured on a closed pocket, test_adaptive). Entries (a helix or ramp down and its
// turn or pass at the bottom) are plunges at the plunge feed and cut with the cutter's end: not bounded.
constexpr double kAdaptiveEngagementSlackDeg = 10.0;

struct AdaptiveOptions {
  double min_turn_radius = NAN;  // mm the cutter's centre turns on at least while cutting; NaN: 0.2 R
  double helix_radius = NAN;     // mm; NaN: 0.5 R (smaller where the material left is narrower)
  double ramp_slope = 0.05;      // descent per unit of travel of a helix or ramp (about 3 degrees)
};

Job adaptive_on(const Surface& surface, const PlanParams& params, const AdaptiveOptions& options,
                const PlanProgress& progress = {}, PlanReport* report = nullptr);
Job adaptive_strategy(const Surface& surface, const PlanParams& params, const PlanProgress& progress,
                      PlanReport* report = nullptr);

// The engagement limit of a plan: params.engagement_deg, else acos(1 - stepover / R) (180 from a stepover of D).
double engagement_limit(const PlanParams& params, const PlanFrame& frame);

}  // namespace rosmill::core
