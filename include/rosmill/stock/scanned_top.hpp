// The top of a stock scanned from above, read at each cell centre of the stock's grid.
//
// The dexel stock and the design are both sampled by a vertical ray through each cell's centre. Taking the highest
// scan point of a cell instead would stand phantom material on every slope, up to a cell's width times the slope's
// tangent (2.8 mm on a 80-degree flank with 0.5 mm cells), and a rest job after a re-scan would chase it all over
// the part. So the points of a cell and its eight neighbours are fitted with a plane z = a + b x + c y by least
// squares and the plane is read at the centre, kept within those points' heights; where fewer than three points,
// or points along a line, leave the plane free, the cell takes the highest of them.
#pragma once
#include <vector>

#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/stock/height_field.hpp"

namespace rosmill::core::stock {

// NaN for a cell without points.
std::vector<float> scanned_top(const PointCloud& cloud, const GridSpec& grid);

}  // namespace rosmill::core::stock
