// Verify a 3+2 program of a trunnion table: the program's moves are machine coordinates at the A and C it indexed
// the part to, so each run of moves between two indexings is the part seen from another side. The verifier follows
// it through its rotary moves: every run is simulated against the design turned as the table holds it at that
// A and C (a gouge is a gouge whatever the stock), and all runs cut one in-process stock in the workpiece frame,
// which is then compared with the design.
#pragma once
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/placement.hpp"
#include "rosmill/machine/trunnion.hpp"
#include "rosmill/stock/program.hpp"
#include "rosmill/verify/verify.hpp"

namespace rosmill::core::verify {

// One run of the program at one turn of the table.
struct IndexedRun {
  double a = 0, c = 0;          // degrees
  size_t moves = 0;
  uint32_t first_source = 0;    // the G-code line of its first move
  DeviationReport report;       // the run on the design turned to (a, c), from a box around it
};

struct IndexedVerifyResult {
  std::vector<IndexedRun> runs;
  double max_gouge_mm = 0;      // the deepest of the runs'
  uint32_t gouge_source = 0;    // its line (0: none)
  // The stock after every run, in the workpiece frame: its volume, the design's, and the material left over the
  // design's top seen from each run's side (min < 0 would be a cut into the design; max: what is left there).
  double stock_mm3 = 0, left_mm3 = 0, design_mm3 = 0;
  double min_left_mm = 0, max_left_mm = 0;
  double seconds = 0;
};

// `workpiece_on_table`: the workpiece frame on the table at A = C = 0 ("table" <- "workpiece"). The stock starts
// as `stock` in the workpiece frame (the design's bounds by default). Throws Error naming the line on a move that
// turns A or C while the tool moves (a simultaneous five-axis move, which a 3+2 program does not make) or on a
// move whose A or C is not known.
IndexedVerifyResult verify_indexed(const Mesh& design, const stock::MachineProgram& program,
                                   const machine::Trunnion& trunnion, const Placement& workpiece_on_table,
                                   const StockSpec& stock = {}, const VerifyOptions& options = {});

}  // namespace rosmill::core::verify
