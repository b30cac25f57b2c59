// Adaptive clearing: z-level roughing at a bounded radial engagement of the cutter. At each level (the step-downs
// and every flat face plus the allowance, levels.hpp) the region to clear is the material standing above the level
// (the job's in-process stock, a stock mesh's section or the stock box) within reach of the cutter, which keeps
// out of the part grown by the allowance (the waterline's cutter-location loops at that level, waterline.hpp).
//
// The path is steered, as in constant-engagement ("adaptive", "dynamic") clearing: the cutter runs in passes with
// the material on its right (climb milling for an M3 spindle), and at every step of R/10 its heading turns as far
// into the material as keeps the engagement (the angle of its leading half-circle in material, measured against a
// bitmap of what is left, level_material.hpp) at the limit less its 2-degree resolution (at most 88 degrees: past a
// side cut of half the tool a pass would wind round its own track), and never by more than the smallest turn
// radius allows. So a pass follows the boundary of the cleared area at a constant engagement:
// it spirals out of an entry, rounds convex material, runs across the front of a channel from wall to wall
// (trochoidal milling, each pass a step further on), and turns away from an inner corner instead of burying the
// tool in it. A pass ends where no turn keeps the engagement under the limit out of the part (a wall ahead, a
// corner) or after a run in air; the next begins in air beside the material nearest where the last began (the
// upstream end of the same front), reached along the level through cleared air where the way is free, else over
// the material. A last pass round the walls, opened by the turn radius, takes what the passes left on them where
// its engagement stays under the limit.
//
// Where no pass can begin (a closed pocket, the first level) the cutter enters by a helix where the room for it is
// deepest, or by a ramp along the longest straight way where no helix fits (a slot barely wider than the tool),
// starting just above the material there. Feeds follow the engagement of each move.
#pragma once
#include "rosmill/plan/plan_report.hpp"
#include "rosmill/plan/plan_support.hpp"

namespace rosmill::core {

// The most the radial engagement of a move at a level passes the limit by, as the verifier measures it
// (verify/engagement.hpp, within its own tolerance besides): the planner measures on a bitmap of R/20 cells (or
// finer at small limits) with 2-degree samples, so a sliver thinner than a cell that a move meets head-on, or a
// job's coarser height grid of material, shows more to the verifier (9.4 degrees on the closed channel of
// test_adaptive, up to 10 on the bundled jobs). Entries (a helix or ramp down and its turn or pass at the bottom)
// are plunges at the plunge feed and cut with the cutter's end: not bounded.
constexpr double kAdaptiveEngagementSlackDeg = 10.0;

struct AdaptiveOptions {
  double min_turn_radius = NAN;  // mm the cutter's centre turns on at least while cutting; NaN: 0.2 R
  double helix_radius = NAN;     // mm; NaN: 0.75 R (smaller where the material left is narrower)
  double ramp_slope = 0.05;      // descent per unit of travel of a helix or ramp (about 3 degrees)
};

Job adaptive_on(const Surface& surface, const PlanParams& params, const AdaptiveOptions& options,
                const PlanProgress& progress = {}, PlanReport* report = nullptr);
Job adaptive_strategy(const Surface& surface, const PlanParams& params, const PlanProgress& progress,
                      PlanReport* report = nullptr);

// The engagement limit of a plan: params.engagement_deg, else acos(1 - stepover / R) (180 from a stepover of D).
double engagement_limit(const PlanParams& params, const PlanFrame& frame);

}  // namespace rosmill::core
