// Any strategy kept to marked cells (MaterialTop::keep): a toolpath planned over the whole part, kept to where an
// earlier tool left rest material (rest machining), or to the faces a setup of a job finishes (its segments and an
// overlap band, so that the seams of several setups blend). A cutting move is kept where the cutter's axis passes
// within its radius (plus one cell) of a marked cell; between kept stretches the cutter leaves by a feed up to clear the material it stands in,
// a rapid over the material on the way (link_clearance above the highest within its reach, checked along the
// whole link) and a rapid down to the approach over the material under the cutter and a plunge into the next
// stretch. A dropped stretch shorter than `bridge` between
// two kept ones is cut anyway: a short feed costs less than the way up and back. The moves kept are the
// strategy's own, cut at sample points on them, so no kept move goes deeper than the strategy's did.
#pragma once
#include "rosmill/plan/material_top.hpp"
#include "rosmill/toolpath/job.hpp"

namespace rosmill::core {

struct KeepOptions {
  double link_clearance = 2.0;  // mm over the material a link keeps
  double approach = 0.5;        // mm over the material under the cutter where the rapid down into a cut stops
  double bridge = NAN;          // mm; NaN: the cutter's diameter
};

// Throws Error when `material` has no cells to keep to.
Toolpath keep_to_cells(const Toolpath& toolpath, const MaterialTop& material, const KeepOptions& options = {});
Job keep_to_cells(const Job& job, const MaterialTop& material, const KeepOptions& options = {});

}  // namespace rosmill::core
