// Material removal simulation on a height field (dexel) stock: every line and XY arc of a program sweeps the
// exact cutter profile (flat, ball, bull) and each cell keeps the lowest cutter bottom that passed over it.
//
// Per move only the cells of the footprint (a capsule around a line, an annular band around an arc) are visited
// and the lowest bottom over the move is found analytically: horizontal moves from the XY distance to the path,
// a ball on a ramp from the swept capsule of its centre, a flat end from the part of the ramp over the cell, a
// bull nose by a golden-section search of its (convex) bottom along the ramp. Helical arcs are split into chords
// within `arc_tolerance`. The grid is cut into bands of rows that the cores process independently, each band
// running its moves in program order, so the result (heights and which move cut each cell) is deterministic.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/verify/height_field.hpp"
#include "rosmill/verify/program.hpp"

namespace rosmill::verify {

struct SimulationOptions {
  double arc_tolerance = 0.001;  // mm: largest distance between a helical arc and its chords
  int band_rows = 8;             // rows per band of work (the unit of parallel work)
  bool parallel = true;
};

struct SimulationResult {
  size_t moves = 0;               // program moves swept
  size_t rapid_cut_cells = 0;     // cells lowered by a rapid (G0): each is a crash into material
  uint32_t first_rapid_cut = Stock::kNoMove;  // program move index of the first rapid that cut, if any
  // Squared XY distance from each cell centre to the nearest axis position of the finishing moves (the feed moves
  // of the last tool); +infinity where they never came. The scallop check reads it.
  std::vector<float> finish_axis_d2;
  uint16_t finishing_tool = 0;
  double seconds = 0.0;
};

// Sweeps every move of `program` through `stock` (heights lowered in place; stock.cut_by records, per cell, the
// index in program.moves of the first move that cut it to its final height).
SimulationResult simulate(const MachineProgram& program, Stock& stock, const SimulationOptions& options = {});

// The lowest cutter bottom (tip height + profile) the move passes over the point (x, y); +infinity when the
// cutter never covers it. The slow, obvious reference of what simulate() computes (tests compare the two).
double lowest_bottom_reference(const SimMove& move, const Cutter& cutter, double x, double y, int samples = 20000);

}  // namespace rosmill::verify
