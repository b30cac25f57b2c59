// The inspection map as a picture: the scan seen from above (+x right, +y up, axes in mm) in the design's frame,
// every point a disc at the scan's spacing in the colour band of its deviation (the verifier's bands: reds below
// the design, blues above), the worst drawn last so they stay on top; the design's outline; beside it the colour
// bar and the inspection's figures; over it the title naming the part, the scan and the date.
#pragma once
#include <string>
#include <vector>

#include "rosmill/geometry/contour.hpp"
#include "rosmill/picture/map_caption.hpp"
#include "rosmill/picture/map_plot.hpp"
#include "rosmill/scan/inspection.hpp"

namespace rosmill::core::verify {

// `outline`: the design seen from above (outline_from_above). Each disc is as wide as the median distance from a
// scan point to its nearest neighbour, so neighbouring discs touch and the map reads as a surface.
picture::MapPicture inspection_picture(const scan::InspectionReport& report, double tolerance,
                                       const std::vector<Contour>& outline, const picture::MapCaption& caption);
// Throws Error naming `path` when it cannot be written.
void write_inspection_png(const std::string& path, const scan::InspectionReport& report, double tolerance,
                          const std::vector<Contour>& outline, const picture::MapCaption& caption);

}  // namespace rosmill::core::verify
