// A solid as Z-dexels: over each square cell of an XY grid, the sorted, disjoint z-intervals of material along
// the vertical line through the cell centre (Van Hook, "Real-time shaded NC milling display", SIGGRAPH 1986).
// Each cell stands for the square prism around its line, so the volume is the cell area times the lengths.
// A box is one interval a cell, a casting a few (ray casting through its triangles), a scanned raw stock one
// (from the table up to the scanned top).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/stock/height_field.hpp"

namespace rosmill::core::stock {

struct Span {
  float lo = 0, hi = 0;  // mm, lo < hi
};

struct Dexels {
  GridSpec grid;
  std::vector<uint32_t> first;  // cells + 1 entries: the spans of cell c are spans[first[c], first[c + 1])
  std::vector<Span> spans;
  double z_min = 0, z_max = 0;  // the z range every span lies in

  const Span* begin(size_t c) const { return spans.data() + first[c]; }
  const Span* end(size_t c) const { return spans.data() + first[c + 1]; }
  double volume() const;  // mm^3
  size_t bytes() const { return first.capacity() * sizeof(uint32_t) + spans.capacity() * sizeof(Span); }
};

// The grid of a stock covering [min, max] at `cell` mm; throws Error naming `where` with the cells and the memory
// the model would take when it is more than `max_cells` cells, before anything is allocated.
GridSpec stock_grid(const Box3& bounds, double cell, size_t max_cells, const std::string& where);

// A box: one span a cell whose centre lies inside it.
Dexels box_dexels(const Box3& box, const GridSpec& grid);

// A closed mesh (a casting, a forging): the hits of each cell's vertical line with its triangles, paired going up
// (Roth, "Ray casting for modeling solids", 1982). Throws Error naming `where` when the mesh is not closed.
Dexels mesh_dexels(const Mesh& mesh, const GridSpec& grid, const std::string& where = "stock mesh");

// Raw stock a scanner saw from above, in the workpiece frame: in each cell from `table_z` up to the highest point
// of the cell. A cell without points takes the mean top of the nearest cells with a top on both sides of it along
// x or along y within `fill_cells` (a hole in the scan), in rounds that read the cells earlier rounds filled (a
// scan sparser than the grid both ways); the cells outside the scanned outline stay empty.
Dexels cloud_dexels(const PointCloud& cloud, double table_z, const GridSpec& grid, int fill_cells = 3);

}  // namespace rosmill::core::stock
