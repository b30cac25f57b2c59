// The cutter's engagement in a job's operations, measured against the stock as it stands before each
// (verify/engagement.hpp), and a roughing operation's feeds set from it by radial chip thinning
// (cutter/chip_thinning.hpp), so that its program's F words and the job's time estimate follow the cut.
#pragma once
#include <cstddef>
#include <optional>
#include <vector>

#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/stock/in_process_stock.hpp"
#include "rosmill/toolpath/job.hpp"
#include "rosmill/verify/engagement.hpp"

namespace rosmill::core::job {

// The stock seen from the current setup on the measurement's finer grid. The in-process stock's cells (the job's
// resolution, 0.5 mm by default) are too coarse for an angle: when a setup begins, its view is read onto the finer
// grid, and every operation of the setup is then swept through that grid in turn, so that a wall an operation leaves
// stands where it was cut for the next one, not where the coarse cells put it.
class EngagementStock {
 public:
  // Reads the stock as it stands, seen from the setup, when the setup is new (its first operation, before that
  // one cuts): from then on the measurement needs no more of the in-process stock.
  void prepare(const stock::MachineProgram& program, const stock::InProcessStock& stock, const SetupFrame& frame,
               size_t setup_index);
  // Measures `program` (in the setup's frame) against the stock before it and sweeps it through.
  verify::EngagementReport measure(const stock::MachineProgram& program);

 private:
  std::optional<size_t> setup_;
  stock::HeightField field_;
};

// Sets the feed of every feed move that travels in XY (plunges and ramps keep the plunge feed) from its measured
// engagement (`move_deg`, one per move of stock::program_from_job(toolpaths)), capped at `max_feed` (mm/min; 0:
// none). Returns how many it set.
size_t set_feeds_from_engagement(Job& toolpaths, const std::vector<float>& move_deg, double max_feed);

}  // namespace rosmill::core::job
