// Planning strategies by name: the one entry point the command line and the ROS planner use. Each strategy
// lives in its own file; src/plan/strategy_table.cpp lists them.
#pragma once
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/plan/toolpath.hpp"

namespace rosmill {

// What to plan on: a mesh or a cloud (millimetres, machined side facing +Z, in the workpiece frame).
struct PlanInput {
  const Mesh* mesh = nullptr;
  const PointCloud* cloud = nullptr;
};

// Parameters; NaN means "the tool's default" (stepover, stepdown) or the strategy's default.
struct PlanParams {
  Tool tool;
  double stepover = NAN;
  double stepdown = NAN;
  double allowance = 0.0;    // stock to leave on every surface (mm)
  double tolerance = 0.001;  // chord / gouge tolerance (mm)
  double angle_deg = 0.0;    // raster direction in the XY plane
  double stock_margin = 5.0; // box stock: the part's bounding box grown by this (mm)
  // Roughing from a stock mesh instead of the box (closed, containing the part, same frame and units; not owned;
  // see plan/stock.hpp). Its bounding box then gives the levels' top and the safe height.
  const Mesh* stock_mesh = nullptr;
  double safe_clearance = 5.0; // safe_z above the stock top (mm)
};

// Progress in [0, 1]; return false to cancel (the strategy then throws Error("plan", "cancelled")).
using PlanProgress = std::function<bool(double fraction)>;

// A job: one toolpath per tool, in machining order (most strategies return one; cloud-all returns three).
using Job = std::vector<Toolpath>;
using StrategyFunction = std::function<Job(const PlanInput&, const PlanParams&, const PlanProgress&)>;

struct StrategyEntry {
  std::string name;
  std::string description;
  bool needs_mesh;  // false: works on a cloud (or on either through the Surface seam)
  bool needs_cloud;
  StrategyFunction function;
};

const std::vector<StrategyEntry>& strategies();
// Throws Error listing the known names when `name` is unknown, or when the input kind does not fit.
Job plan(const std::string& name, const PlanInput& input, const PlanParams& params,
              const PlanProgress& progress = {});

}  // namespace rosmill
