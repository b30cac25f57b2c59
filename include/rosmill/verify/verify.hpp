// Verify a program before it runs: simulate it on the stock, compare the result with the design, report.
// The one entry point the command line and the ROS layer call.
#pragma once
#include <string>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/stock/in_process_stock.hpp"
#include "rosmill/stock/material_removal.hpp"
#include "rosmill/stock/program.hpp"
#include "rosmill/verify/deviation.hpp"
#include "rosmill/verify/engagement.hpp"

namespace rosmill::core::verify {

// The stock before the program: the design's bounding box (default), an explicit box, or a stock mesh whose
// top surface is the starting height (cells it does not cover hold no material: they start at its floor).
struct StockSpec {
  enum class Kind { DesignBounds, Box, Mesh } kind = Kind::DesignBounds;
  Box3 box;
  const rosmill::core::Mesh* mesh = nullptr;

  // "box" (the design's bounds) or "x0,y0,z0,x1,y1,z1" (mm). A file name is left to the caller (kind Mesh).
  static StockSpec parse_box(const std::string& text, const std::string& where = "--stock");
};

struct VerifyOptions {
  double resolution = 0.5;  // cell size in mm
  size_t max_cells = stock::kMaxGridCells;
  CompareOptions compare;
  stock::SimulationOptions simulation;
  // Also measure the radial engagement along the program (engagement.hpp) on a finer grid of the same stock.
  bool measure_engagement = false;
  EngagementOptions engagement;
};

struct VerifyResult {
  DeviationReport report;
  DeviationGrid grid;
  double simulation_seconds = 0.0;
  size_t cells_visited = 0;  // cell evaluations of the simulation
  EngagementReport engagement;  // with VerifyOptions::measure_engagement
  double seconds = 0.0;  // the whole verification (grid, design heights, simulation, comparison)
};

// The stock as an in-process stock (workpiece frame) at options.resolution: a stock mesh as it is, else the box
// (the design's bounds by default). What the verifiers that follow a part through turns or tool axes cut.
stock::InProcessStock in_process_stock(const rosmill::core::Mesh& design, const StockSpec& stock,
                                       const VerifyOptions& options);

VerifyResult verify_program(const rosmill::core::Mesh& design, const stock::MachineProgram& program,
                            const StockSpec& stock,
                            const VerifyOptions& options = {});
VerifyResult verify_program(const PointCloud& design, const stock::MachineProgram& program, const StockSpec& stock,
                            const VerifyOptions& options = {});

}  // namespace rosmill::core::verify
