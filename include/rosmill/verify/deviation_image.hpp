// The deviation map as a picture: the grid seen from above (+x right, +y up) in the colours of deviation_map.hpp,
// the deepest gouge ringed, and beside it the legend (every colour band with its range in mm) and the report's
// figures.
#pragma once
#include <string>

#include "rosmill/verify/deviation.hpp"
#include "rosmill/verify/rgb_image.hpp"

namespace rosmill::core::verify {

// The map is drawn at a whole number of pixels a cell (up to 8) for small grids, and in blocks of cells (each its
// worst cell, so a gouge stays visible) for grids larger than 800 pixels.
RgbImage deviation_image(const DeviationGrid& grid, const DeviationReport& report);
void write_deviation_png(const std::string& path, const DeviationGrid& grid, const DeviationReport& report);

}  // namespace rosmill::core::verify
