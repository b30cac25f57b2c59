// What a strategy did, for reports and tests: its lines and levels, drop-cutter queries, and the cutter locations
// the sampling policy added (step_error.hpp) or left out (a surface's skipped regions).
#pragma once
#include <cstddef>
#include <string>

namespace rosmill::core {

struct PlanReport {
  std::string strategy;
  size_t lines = 0;            // raster lines
  size_t levels = 0;           // z levels (roughing)
  size_t samples = 0;          // drop-cutter queries of the sampling
  size_t cl_points = 0;        // moves written
  size_t buffer_points = 0;    // step-error sampling: locations inserted by the interpolation (error > t/2)
  size_t checked_points = 0;   // step-error sampling: locations inserted by the check of the moves
  size_t skipped_samples = 0;  // positions left out where the surface skips (Surface::skips)
  double sample_step = 0.0;    // mm
};

}  // namespace rosmill::core
