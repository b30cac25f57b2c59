// Flood fill over a grid of nx x ny cells (index j * nx + i), across the cells' sides.
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace rosmill::core {

// Calls visit(c) once for each cell joined to `start` across cell sides through cells for which joins(c) holds,
// `start` included (the caller has checked it). `seen` (nx * ny, 0 where not yet reached) marks them; `open` is
// scratch space.
template <class Joins, class Visit>
void flood_cells(long nx, long ny, size_t start, std::vector<uint8_t>& seen, std::vector<size_t>& open,
                 const Joins& joins, const Visit& visit) {
  seen[start] = 1;
  open.assign(1, start);
  while (!open.empty()) {
    const size_t c = open.back();
    open.pop_back();
    visit(c);
    const long i = long(c) % nx, j = long(c) / nx;
    for (const auto& [di, dj] : {std::pair{1L, 0L}, {-1L, 0L}, {0L, 1L}, {0L, -1L}}) {
      const long ii = i + di, jj = j + dj;
      if (ii < 0 || jj < 0 || ii >= nx || jj >= ny) continue;
      const size_t n = size_t(jj) * size_t(nx) + size_t(ii);
      if (!seen[n] && joins(n)) seen[n] = 1, open.push_back(n);
    }
  }
}

}  // namespace rosmill::core
