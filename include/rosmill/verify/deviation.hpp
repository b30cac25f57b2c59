// Machined minus design, cell by cell, and the figures a machinist reads before running a program: the deepest
// gouge and the line that made it, the material left, the scallop of the finishing passes, the area never cut.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/stock/height_field.hpp"
#include "rosmill/stock/material_removal.hpp"
#include "rosmill/stock/program.hpp"

namespace rosmill::core::verify {

struct CompareOptions {
  double tolerance = 0.01;  // mm: deviations within ±tolerance count as on the design
  double stepover = 0.0;    // mm of the finishing passes; 0: the program's own (toolpath files), else unknown
};

// Per-cell deviation on the stock's grid (for images, and for the ROS layer's coloured cloud). NaN in `design`
// and `deviation` where the design is unknown (cloud gaps).
struct DeviationGrid {
  stock::GridSpec grid;
  std::vector<float> machined;
  std::vector<float> design;
  std::vector<float> deviation;  // machined - design: < 0 gouge, > 0 material left
  std::vector<uint8_t> cut;      // 1 where some move lowered the cell
  double tolerance = 0.01;
};

struct DeviationReport {
  // Gouge: the deepest cell below the design by more than the tolerance (0 and no location when none).
  double max_gouge_mm = 0.0;
  bool gouged = false;
  Vec3 gouge_at = Vec3::Zero();     // cell centre at the machined height
  uint32_t gouge_move = stock::HeightField::kNoMove;  // index in the program's moves
  uint32_t gouge_source = 0;        // its G-code line or toolpath move number (0 when unknown)
  bool from_gcode = false;          // gouge_source is a G-code line (else a toolpath move number)
  size_t gouge_cells = 0;
  // Material left (machined above design), over the compared cells.
  double max_rest_mm = 0.0;
  double mean_rest_mm = 0.0;
  // Scallop: the highest rest of the cells the finishing tool (the last tool) cut that lie within stepover/2 of its
  // path (R/2 when the stepover is unknown) where the design is nearly flat (slope under 0.2) within the cutter
  // radius, since the theory is for a flat floor and material a cutter cannot reach by a wall is no scallop. Theory:
  // the profile at s/2.
  double scallop_mm = 0.0;
  double scallop_theory_mm = -1.0;  // -1 when the stepover is unknown
  double stepover_mm = 0.0;
  // Cells that still have material to remove (rest above the tolerance) and that no move ever cut.
  double unreached_area_mm2 = 0.0;
  size_t cells = 0;           // cells of the grid
  size_t compared_cells = 0;  // cells with a known design height
  size_t rapid_cut_cells = 0;
  uint32_t first_rapid_cut_source = 0;
};

// Theoretical scallop of parallel passes at `stepover` on a flat floor: the profile's height half-way between two
// passes (for a ball of radius R: R - sqrt(R^2 - (s/2)^2); capped at the full radius's when s > 2R).
double scallop_theory(const Cutter& cutter, double stepover);

// How far from the finishing path a cell counts as between two of its passes: half the stepover (half the
// finishing cutter's radius when the stepover is unknown) plus half a cell. The simulation's trace radius.
double scallop_window(const stock::MachineProgram& program, const CompareOptions& options, double cell);

DeviationReport compare(const stock::HeightField& stock, const std::vector<float>& design,
                        const stock::MachineProgram& program,
                        const stock::SimulationResult& sim, const CompareOptions& options = {},
                        DeviationGrid* grid = nullptr);

}  // namespace rosmill::core::verify
