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

// Highest point of the cloud in each cell; empty cells take the highest of their neighbours up to `fill_cells`
// cells away (scans have gaps smaller than a few cells); cells further from any point stay NaN (not compared).
std::vector<float> design_heights(const PointCloud& cloud, const GridSpec& grid, int fill_cells = 3);

}  // namespace rosmill::core::stock
