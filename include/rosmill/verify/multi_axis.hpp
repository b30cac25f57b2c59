// Verify a multi-axis program (the tool axis turning along its moves: five- and four-axis finishing). It cuts an
// in-process stock in the workpiece frame by the flutes' sweep (stock/multi_axis_sweep.hpp), which is then read
// along the outward normal at every sample of the design's surface (geometry/surface_samples.hpp): how much
// material is left on it and how deep a cut went into it, with the move that cut deepest. Walls and undercuts count,
// not only what a view from above sees; the sweep shares no code with the planners.
#pragma once
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/surface_samples.hpp"
#include "rosmill/stock/in_process_stock.hpp"
#include "rosmill/stock/multi_axis_program.hpp"
#include "rosmill/verify/verify.hpp"

namespace rosmill::core::verify {

struct MultiAxisVerifyResult {
  size_t moves = 0, samples = 0;
  double area_mm2 = 0;                       // the design's surface
  double max_gouge_mm = 0;                   // deepest cut into the design beyond the tolerance (0: none)
  Vec3 gouge_at = Vec3::Zero();              // the design's point above it
  uint32_t gouge_source = 0;                 // the move that cut there (0: none)
  double gouged_area_mm2 = 0;                // cut deeper than the tolerance
  double max_rest_mm = 0, mean_rest_mm = 0;  // material left on the surface (mean over its area)
  Vec3 max_rest_at = Vec3::Zero();
  double limit_mm = 0;        // what counts as finished: the tolerance, plus the scallop where the stepover is known
  double above_area_mm2 = 0;  // left above the limit
  double unreached_area_mm2 = 0;       // of it, where no tool came within 1 mm
  double stock_mm3 = 0, left_mm3 = 0;  // the stock after the program, and that less the design
  stock::RemovalReport removal;        // the rapids into material among it
  double seconds = 0;
  // Each sample of the surface with what is left on it and how deep it was cut (0: no deeper than the tolerance).
  SurfaceSamples surface;
  std::vector<float> rest, gouge;
};

// The stock starts as `stock` (the design's bounds by default), at options.resolution; `stepover` (mm, 0: unknown)
// adds the ball's scallop on a flat, r - sqrt(r^2 - stepover^2 / 4), to the limit.
MultiAxisVerifyResult verify_multi_axis(const Mesh& design, const stock::MultiAxisProgram& program,
                                        const StockSpec& stock = {}, const VerifyOptions& options = {},
                                        double stepover = 0);

}  // namespace rosmill::core::verify
