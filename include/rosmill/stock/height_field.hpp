// A height field (dexel) grid over the XY plane: one value per square cell, sampled at the cell centre.
// The stock seen from a setup, the removal envelope of a setup, the design and the deviation are held on such a
// grid so that they compare cell by cell.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::stock {

// The largest grid allocated (the verifier holds about 32 bytes a cell for the stock, the design, the deviation and
// the trace): a larger one is refused with a message, never allocated from what an input asks for.
constexpr size_t kMaxGridCells = 25'000'000;

struct GridSpec {
  double x0 = 0.0, y0 = 0.0;  // lower-left corner of cell (0, 0) in mm
  double cell = 1.0;          // cell edge length in mm (the resolution)
  int nx = 0, ny = 0;

  size_t cells() const { return static_cast<size_t>(nx) * static_cast<size_t>(ny); }
  size_t index(int i, int j) const { return static_cast<size_t>(j) * nx + i; }
  double cx(int i) const { return x0 + (i + 0.5) * cell; }
  double cy(int j) const { return y0 + (j + 0.5) * cell; }
  // Index range [lo, hi] of the cells whose centres lie in [a, b] along x (or y); empty when lo > hi (also for
  // NaN or far-off bounds: the index is clamped before it becomes an int).
  int first_x(double a) const { return first_index((a - x0) / cell, nx); }
  int last_x(double b) const { return last_index((b - x0) / cell, nx); }
  int first_y(double a) const { return first_index((a - y0) / cell, ny); }
  int last_y(double b) const { return last_index((b - y0) / cell, ny); }

  // A grid covering [min, max] in XY at `cell` mm (at least one cell each way). Throws Error naming `where` for a
  // cell size that is not a positive number or a grid of more than `max_cells` cells (with the memory it would take
  // at `bytes_per_cell`, when given).
  static GridSpec covering(const Vec2& min, const Vec2& max, double cell, size_t max_cells = kMaxGridCells,
                           const std::string& where = "--resolution", size_t bytes_per_cell = 0);

 private:
  static int first_index(double u, int n) {
    const double v = std::ceil(u - 0.5);
    return !(v > 0) ? 0 : v >= n ? n : static_cast<int>(v);
  }
  static int last_index(double u, int n) {
    const double v = std::floor(u - 0.5);
    return !(v >= 0) ? -1 : v >= n - 1 ? n - 1 : static_cast<int>(v);
  }
};

// The stock being cut, seen from the tool: the top height of material per cell and, per cell, the move that last
// lowered it.
struct HeightField {
  GridSpec grid;
  double bottom = 0.0;             // stock floor (mm); cells without material sit at the floor
  std::vector<float> top;          // current top of material per cell (mm)
  std::vector<uint32_t> cut_by;    // index of the program move that last lowered the cell, kNoMove if none
  static constexpr uint32_t kNoMove = 0xffffffffu;

  // A box of stock: every cell at `top_z`, floor at `bottom_z`.
  static HeightField box(const GridSpec& grid, double bottom_z, double top_z);
};

}  // namespace rosmill::core::stock
