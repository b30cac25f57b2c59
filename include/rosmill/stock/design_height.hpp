// The design's top surface on the verification grid: what the machined stock is compared with, cell by cell.
#pragma once
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/stock/height_field.hpp"

namespace rosmill::core::stock {

// Highest point of the mesh met by a vertical ray at each cell centre (triangles are rasterised over the cells
// of their XY bounds, so each cell only meets the triangles above it). Cells the mesh does not cover get `floor`
// (the table the part stands on: what a 3-axis program should cut down to there).
std::vector<float> design_heights(const Mesh& mesh, const GridSpec& grid, double floor);

// The design's highest over each cell as its centre (`centre`: design_heights on the same grid) and four corners
// see it (the rays of a grid offset by half a cell). On a slope the design rises across a cell by its width times the slope: a stock sampled at the centre
// stands above the design's centre height by up to that much without any material being left there, which this
// bound does not count as material.
std::vector<float> design_highest_in_cells(const Mesh& mesh, const GridSpec& grid, double floor,
                                            std::vector<float> centre);

// Highest point of the cloud in each cell; empty cells take the highest of their neighbours up to `fill_cells`
// cells away (scans have gaps smaller than a few cells); cells further from any point stay NaN (not compared).
std::vector<float> design_heights(const PointCloud& cloud, const GridSpec& grid, int fill_cells = 3);

}  // namespace rosmill::core::stock
