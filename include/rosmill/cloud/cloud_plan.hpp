// The seed's three-stage plan straight from a point cloud (../shared/seeds/004): roughing with a flat end mill
// in levels, then semi-finishing and finishing with ball end mills, all on the grid method over a CloudSurface.
//
// Rough (seed 3.3.1): raster lines in x, forward then backward (zigzag), lines 2R - 0.5δ apart starting at
// y_min + 0.5δ, from x_min - R - δ to x_max + R + δ (outside the stock: entry from the free boundary); levels
// z_max - d, z_max - 2d, ... down to the floor. At every sample the cutter goes to max(level, T) where T is the
// drop of the cutter grown by δ, lifted by δ (never closer than δ to a point); between samples it moves up first
// or down last (a staircase), and the samples are close enough that the footprints of two neighbours cover the
// band swept between them (cloud_plan.cpp): no straight move can cut a point. Stretches where the level cuts
// nothing new are skipped (retract, rapid at safe_z, feed down to 1 mm over the level above, plunge).
//
// Semi-finish / finish (seed 3.3.2-3.3.3): zigzag raster with a ball (5 mm, then 3 mm), CL at z_p + sqrt(R² - d²)
// - R + δ (highest point wins; never below the floor, the cloud's lowest point, + δ); CL points every 2R along a line (the seed's interval on flat ground) and buffer
// points inserted by the seed's interpolation: for two CL P1, P2 and the true CL Pi between them, the step error
// ε = Pi.z - (P1.z - (P1.x - Pi.x)(P1.z - P2.z)/(P1.x - P2.x)); where |ε| exceeds half the tolerance the worst Pi
// becomes a buffer point and both halves are checked again (a binary tree). Pi are drops on a fine sampling step
// h = sqrt(4 R t) (over level ground a ball's CL sags h²/8R = t/2 between two of them). Then every move is
// checked against the points themselves (the seed's "paths between grids are checked", cloud_sweep.hpp): where
// a point would go more than t into the cutter, a buffer point is dropped where it goes deepest. So every CL
// point is an exact drop (no point inside the cutter), every move stays within t of the points, and at every
// fine sample the moves are within t/2 of the drop.
//
// Missing data (cloud_surface.hpp): holes are bridged by lids at the highest neighbouring point (HolePolicy
// Bridge) or left out (Skip: no cutter location whose footprint reaches a hole; the tool retracts over it); sparse
// regions are bridged by the points' support discs. Both are reported (CloudPrepReport, CloudStageReport).
#pragma once
#include <string>
#include <vector>

#include "rosmill/cloud/cloud_holes.hpp"
#include "rosmill/cloud/cloud_prep.hpp"
#include "rosmill/cloud/cloud_surface.hpp"
#include "rosmill/plan/strategy.hpp"

namespace rosmill {

struct CloudStage {
  Tool tool;
  double stepover = 0.0;   // mm between raster lines; rough: 0 means the seed's grid 2R - 0.5δ
  double allowance = 0.0;  // δ, stock left on every point (mm)
};

struct CloudPlanOptions {
  CloudStage rough;   // flat 10 mm, grid 2R - 0.5δ, δ = 0.5
  CloudStage semi;    // ball 5 mm, stepover 2 mm (scallop 0.21 mm on flat ground), δ = 0.2
  CloudStage finish;  // ball 3 mm, stepover 0.3 mm (scallop 0.0075 mm), δ = 0
  double depth_of_cut = 2.0;  // d, rough step-down (mm)
  double tolerance = 0.01;    // t, machining tolerance: the step error bound (mm)
  double angle_deg = 0.0;     // raster direction of semi and finish (the rough runs in x, as the seed)
  double safe_clearance = 5.0;  // safe_z above the stock top (mm)
  HolePolicy holes = HolePolicy::Bridge;
  double sampling_radius = NAN; // the cloud's sampling radius for the support discs (mm); NaN: estimated

  CloudPlanOptions();  // the seed's defaults
};

struct CloudStageReport {
  std::string strategy;
  size_t lines = 0;          // raster lines
  size_t levels = 0;         // rough only
  size_t samples = 0;        // drop-cutter queries
  size_t cl_points = 0;      // moves written: the cutter locations kept, retracts and approaches
  size_t buffer_points = 0;  // of which inserted by the interpolation (ε > t/2)
  size_t checked_points = 0; // of which inserted by the check of the moves (a point more than t into the cutter)
  size_t skipped_samples = 0;  // HolePolicy::Skip: samples left out because the footprint reaches a hole
  double sample_step = 0.0;  // mm
};

// Throws Error naming the stage on a bad option, Error("plan", "cancelled") when `progress` returns false.
Toolpath plan_cloud_rough(const CloudSurface& surface, const CloudPlanOptions& options, const PlanProgress& progress = {},
                          CloudStageReport* report = nullptr);
// A ball stage (semi or finish): `stage` names the tool, stepover and allowance; `strategy` the toolpath's name.
Toolpath plan_cloud_raster(const CloudSurface& surface, const CloudStage& stage, const std::string& strategy,
                           const CloudPlanOptions& options, const PlanProgress& progress = {},
                           CloudStageReport* report = nullptr);
// Rough, semi and finish, in that order (progress weighted by their sample counts' usual share).
Job plan_cloud_all(const CloudSurface& surface, const CloudPlanOptions& options, const PlanProgress& progress = {},
                   std::vector<CloudStageReport>* reports = nullptr);

// The API for a node: a raw cloud (any units, NaNs allowed) in; prepared cloud, the three toolpaths and the
// reports out. Progress: preparation 0-5 %, then the stages.
struct CloudJob {
  PointCloud cloud;  // prepared, in the workpiece frame (mm)
  CloudPrepReport prep;
  std::vector<CloudStageReport> stages;
  std::vector<Hole> holes;  // as bridged or skipped by the planner
  double sampling_radius = 0.0;  // of the prepared cloud (mm): the support discs' size (cloud_surface.hpp)
  Job job;                  // rough, semi, finish
};
CloudJob plan_cloud_job(const std::vector<Vec3>& raw, const CloudPrepOptions& prep, const CloudPlanOptions& options,
                        const PlanProgress& progress = {});

// The surface options a plan uses: the sink allowed between points is the plan's tolerance.
CloudSurfaceOptions cloud_surface_options(const CloudPlanOptions& options, double hole_cell = 0.0);

// PlanParams -> options: tolerance (NaN: the seed's 0.01), angle, safe clearance copied; `allowance` is the stock
// left on the final part (finish δ), semi leaves 0.2 mm and rough 0.5 mm more; `stepdown` is the rough depth of
// cut. For one stage ("rough", "semi", "finish"), a tool other than the default-constructed one replaces that
// stage's (a ball stage then takes the tool's stepover, the rough its step-down unless given), and `stepover`
// replaces its stepover. For "all" the seed's three tools are used and params.tool is not looked at. Throws
// Error naming the parameter on a bad value.
CloudPlanOptions cloud_options_from_params(const PlanParams& params, const std::string& stage,
                                           HolePolicy holes = HolePolicy::Bridge);

// One of cloud-rough, cloud-semi, cloud-finish, cloud-all on a prepared cloud, with the given hole policy: what the
// strategy table runs (with Bridge) and what the command line runs.
Job plan_cloud_strategy(const std::string& name, const PointCloud& cloud, const PlanParams& params, HolePolicy holes,
                        const PlanProgress& progress = {});

// The strategy-table entry points (cloud-rough, cloud-semi, cloud-finish, cloud-all), HolePolicy::Bridge.
Job cloud_rough_strategy(const PlanInput& input, const PlanParams& params, const PlanProgress& progress);
Job cloud_semi_strategy(const PlanInput& input, const PlanParams& params, const PlanProgress& progress);
Job cloud_finish_strategy(const PlanInput& input, const PlanParams& params, const PlanProgress& progress);
Job cloud_all_strategy(const PlanInput& input, const PlanParams& params, const PlanProgress& progress);

}  // namespace rosmill
