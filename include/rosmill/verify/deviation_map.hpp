// The deviation map a machinist looks at: each cell coloured by how far the machined surface is from the design,
// in bands of decades of the tolerance, gouges in reds and material left in blues. One colour scheme for the
// maps (deviation_image.hpp, inspection_image.hpp) and for the coloured cloud the ROS layer publishes.
#pragma once
#include <string>
#include <vector>

#include "rosmill/picture/rgb.hpp"
#include "rosmill/verify/deviation.hpp"

namespace rosmill::core::verify {

using picture::Rgb;
// The colour bands, in legend order (deepest gouge first): each with its colour and its label in mm.
using DeviationBand = picture::ColourBand;
std::vector<DeviationBand> deviation_bands(double tolerance);

// Index into deviation_bands() of a cell: `deviation` machined - design (NaN: no design there), `cut` whether any
// move lowered the cell (material left on a cell never cut is "not cut").
size_t deviation_band(double deviation, bool cut, double tolerance);

// One cell of the map for display: the cell centre at the machined height (mm), its deviation and colour.
struct DeviationPoint {
  Vec3 position = Vec3::Zero();
  float deviation = 0;
  Rgb colour;
};

// The cells with a known design as points, at most `max_points` of them (0: all): above that the grid is read in
// square blocks, each giving its worst cell (the deepest gouge, else the most material left), so a gouge is
// never averaged away. The ROS layer converts the positions to metres and publishes them as a coloured cloud.
std::vector<DeviationPoint> deviation_points(const DeviationGrid& grid, size_t max_points = 0);

// The worst cell of the block of `step` x `step` cells whose lower-left cell is (i, j) (clipped to the grid):
// the deepest gouge if any, else the most material left; -1 when no cell of the block has a design height.
long worst_cell(const DeviationGrid& grid, int i, int j, int step);

}  // namespace rosmill::core::verify
