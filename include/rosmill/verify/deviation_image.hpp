// The deviation map as a picture: the grid seen from above (+x right, +y up, axes in mm) in the colours of
// deviation_map.hpp, each cell a rectangle at its size, the part's outline, the deepest gouge ringed; beside it the colour bar of the bands with their ranges in mm and the
// report's figures; over it the title naming the part, the program and the date.
#pragma once
#include <string>

#include "rosmill/geometry/contour.hpp"
#include "rosmill/picture/map_caption.hpp"
#include "rosmill/picture/map_plot.hpp"
#include "rosmill/verify/deviation.hpp"

namespace rosmill::core::verify {

// The map is 800 pixels on its longer side; a grid with more cells than that is drawn in square blocks of cells,
// each in the colour of its worst cell (worst_cell), so a gouge stays visible. `outline`: the design's outline
// seen from above (outline_from_above of a mesh design); empty: the edge of the cells where the design has a
// height (a cloud design, known only where it was scanned).
picture::MapPicture deviation_picture(const DeviationGrid& grid, const DeviationReport& report,
                                      const std::vector<Contour>& outline, const picture::MapCaption& caption);
// Throws Error naming `path` when it cannot be written.
void write_deviation_png(const std::string& path, const DeviationGrid& grid, const DeviationReport& report,
                         const std::vector<Contour>& outline, const picture::MapCaption& caption);

}  // namespace rosmill::core::verify
