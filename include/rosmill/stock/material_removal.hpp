// Material removal simulation on a height field (dexel) stock: every line and XY arc of a program sweeps the
// exact cutter profile (flat, ball, bull) and each cell keeps the lowest cutter bottom that passed over it.
//
// Per move only the cells of its footprint are visited, row by row, and the lowest bottom over each is found in
// closed form: the nearest point of a level line or arc, the clamped stationary point of a ball on a ramp, the
// lower end of the covered part of a ramp for a flat end, the drop-cutter edge contact (mirrored) for a bull nose
// on a ramp. Helical arcs are split into chords within `arc_tolerance`. Along a chain of lines a line is only
// swept where it can hold the chain's lowest point (see material_removal.cpp), which makes a dense finishing
// program cost about its swept area, not its moves times the cutter's disc. The grid is cut into bands of rows
// that the cores process independently, each band running its moves in program order, so the result (heights
// and which move cut each cell) is deterministic.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "rosmill/stock/height_field.hpp"
#include "rosmill/stock/program.hpp"

namespace rosmill::core::stock {

struct SimulationOptions {
  double arc_tolerance = 0.001;  // mm: largest distance between a helical arc and its chords
  int band_rows = 32;            // rows per band of work (the unit of parallel work)
  bool parallel = true;
  bool prune = true;             // false: sweep every move over its whole footprint (the slow reference)
  double trace_radius = 0;       // mm: how far from the finishing path cells record their distance (0: R)
  bool trace_finishing = true;   // false: no finishing trace (SimulationResult::finish_axis_d2 stays empty)
  bool mark_cutting_moves = false;  // true: SimulationResult::cutting_moves says which moves lowered a cell
};

struct SimulationResult {
  size_t moves = 0;               // program moves swept
  size_t rapid_cut_cells = 0;     // cells lowered by a rapid (G0): each is a crash into material
  uint32_t first_rapid_cut = HeightField::kNoMove;  // program move index of the first rapid that cut, if any
  // Squared XY distance from each cell centre to the nearest axis position of the finishing moves (the feed moves
  // of the last tool), recorded up to the trace radius; +infinity elsewhere. The scallop check reads it.
  std::vector<float> finish_axis_d2;
  uint16_t finishing_tool = 0;
  std::vector<uint8_t> cutting_moves;  // per move 1 when it lowered some cell (with mark_cutting_moves)
  size_t cells_visited = 0;       // cell evaluations (the work done)
  double seconds = 0.0;
};

// Sweeps every move of `program` through `stock` (heights lowered in place; stock.cut_by records, per cell, the
// index in program.moves of the first move that cut it to its final height).
SimulationResult simulate(const MachineProgram& program, HeightField& stock,
                          const SimulationOptions& options = {});

// Sweeps a program's moves one at a time, in program order, on the calling thread: for a caller that reads the
// stock between moves (the engagement measurement) without simulate()'s per-call setup of bands and threads. A move
// that starts where the one before it ended, with the same tool, sweeps only the cells it can be the lowest over
// (SimulationOptions::prune): the cells it leaves are the ones the move before or after it lowers at least as far,
// so once both are swept the stock is as simulate() leaves it. No finishing trace. `program` and `stock` must
// outlive the sweeper, and the stock keep its size; its cut_by records the index of the move that lowered a cell.
class MoveSweeper {
 public:
  MoveSweeper(const MachineProgram& program, HeightField& stock, double arc_tolerance = 0.001);
  ~MoveSweeper();
  MoveSweeper(const MoveSweeper&) = delete;
  MoveSweeper& operator=(const MoveSweeper&) = delete;
  // Lowers the stock under move k of the program; k must be the move after the last one swept (Error if not).
  // Returns the cells it lowered.
  size_t sweep(size_t k);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The lowest cutter bottom (tip height + profile) the move passes over the point (x, y); +infinity when the
// cutter never covers it. The slow, obvious reference of what simulate() computes (tests compare the two).
double lowest_bottom_reference(const CanonMove& move, const Cutter& cutter, double x, double y, int samples = 20000);

}  // namespace rosmill::core::stock
