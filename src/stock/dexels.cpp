#include "rosmill/stock/dexels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rosmill/error.hpp"
#include "rosmill/stock/design_height.hpp"
#include "rosmill/stock/scanned_top.hpp"
#include "rosmill/stock/vertical_hits.hpp"

namespace rosmill::core::stock {
namespace {

// Builds the CSR of a model from a function giving each cell's spans.
template <class CellSpans>
Dexels build(const GridSpec& grid, CellSpans&& cell_spans) {
  Dexels d;
  d.grid = grid;
  d.first.assign(grid.cells() + 1, 0);
  d.z_min = std::numeric_limits<double>::infinity();
  d.z_max = -d.z_min;
  std::vector<Span> cell;
  for (size_t c = 0; c < grid.cells(); ++c) {
    cell.clear();
    cell_spans(c, cell);
    for (const Span& s : cell) {
      if (!(s.hi > s.lo)) continue;
      d.spans.push_back(s);
      d.z_min = std::min(d.z_min, double(s.lo));
      d.z_max = std::max(d.z_max, double(s.hi));
    }
    d.first[c + 1] = static_cast<uint32_t>(d.spans.size());
  }
  if (d.spans.empty()) d.z_min = d.z_max = 0;
  return d;
}

}  // namespace

double Dexels::volume() const {
  double length = 0;
  for (const Span& s : spans) length += double(s.hi) - double(s.lo);
  return length * grid.cell * grid.cell;
}

GridSpec stock_grid(const Box3& bounds, double cell, size_t max_cells, const std::string& where) {
  if (bounds.empty() || !bounds.min.allFinite() || !bounds.max.allFinite())
    throw Error(where, "the stock is empty or not finite");
  // A cell of the model holds its offset and, mostly, one span; each setup that cuts adds a float a cell.
  return GridSpec::covering(bounds.min.head<2>(), bounds.max.head<2>(), cell, max_cells, where,
                            sizeof(uint32_t) + sizeof(Span) + sizeof(float));
}

Dexels box_dexels(const Box3& box, const GridSpec& g) {
  const Span s{static_cast<float>(box.min.z()), static_cast<float>(box.max.z())};
  return build(g, [&](size_t c, std::vector<Span>& out) {
    const int i = static_cast<int>(c % g.nx), j = static_cast<int>(c / g.nx);
    if (g.cx(i) >= box.min.x() && g.cx(i) <= box.max.x() && g.cy(j) >= box.min.y() && g.cy(j) <= box.max.y())
      out.push_back(s);
  });
}

Dexels mesh_dexels(const Mesh& mesh, const GridSpec& g, const std::string& where) {
  if (mesh.face_count() == 0 || !mesh.closed())
    throw Error(where, "the stock mesh must be closed (every edge shared by two triangles) to hold material");
  // Rays off the lattice of the grid (the shift is a small irrational part of a cell) so that none runs through an
  // edge or a vertex, where a triangle would count twice or not at all.
  const Vec2 shift = g.cell * Vec2(std::sqrt(2.0) * 1e-4, std::sqrt(3.0) * 1e-4);
  struct Hit {
    float z;
    bool up;
  };
  std::vector<uint32_t> first(g.cells() + 1, 0);
  for_each_vertical_hit(mesh, g, shift, 0.0, [&](size_t c, double, bool) { ++first[c + 1]; });
  for (size_t c = 0; c < g.cells(); ++c) first[c + 1] += first[c];
  std::vector<Hit> hits(first.back());
  std::vector<uint32_t> fill(first.begin(), first.end() - 1);
  for_each_vertical_hit(mesh, g, shift, 0.0,
                        [&](size_t c, double z, bool up) { hits[fill[c]++] = {static_cast<float>(z), up}; });
  // Going up the line, a triangle facing down enters the solid and one facing up leaves it; material is where the
  // count is not zero (the non-zero rule holds for either orientation of a consistently oriented mesh).
  return build(g, [&](size_t c, std::vector<Span>& out) {
    auto b = hits.begin() + first[c], e = hits.begin() + first[c + 1];
    std::sort(b, e, [](const Hit& p, const Hit& q) { return p.z < q.z; });
    int winding = 0;
    float enter = 0;
    for (auto h = b; h != e; ++h) {
      const int before = winding;
      winding += h->up ? -1 : 1;
      if (before == 0 && winding != 0) enter = h->z;
      if (before != 0 && winding == 0) out.push_back({enter, h->z});
    }
  });
}

Dexels cloud_dexels(const PointCloud& cloud, double table_z, const GridSpec& g, int fill_cells) {
  if (cloud.points.empty()) throw Error("stock cloud", "the cloud has no points");
  if (!std::isfinite(table_z)) throw Error("stock cloud", "the table height is not a number");
  std::vector<float> top = scanned_top(cloud, g);
  // A hole: the nearest cells with a top on both sides along a row or a column, within fill_cells.
  auto filled = [&](int i, int j) {
    double sum = 0;
    int n = 0;
    for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{0, 1}}) {
      float a = NAN, b = NAN;
      for (int k = 1; k <= fill_cells && (std::isnan(a) || std::isnan(b)); ++k) {
        const int ia = i - k * di, ja = j - k * dj, ib = i + k * di, jb = j + k * dj;
        if (std::isnan(a) && ia >= 0 && ja >= 0) a = top[g.index(ia, ja)];
        if (std::isnan(b) && ib < g.nx && jb < g.ny) b = top[g.index(ib, jb)];
      }
      if (!std::isnan(a) && !std::isnan(b)) sum += a + b, n += 2;
    }
    return n ? static_cast<float>(sum / n) : NAN;
  };
  // In rounds, each reading the cells the rounds before filled, until none changes: a scan sparser than the grid
  // both ways (a scanner's 2 mm pitch on a 0.5 mm grid) has cells with no point in their row nor their column; the
  // first round fills the rows and columns through the points, the next the cells between them. A cell outside the
  // scanned outline has no top on its outer side, in any round.
  std::vector<float> next;
  for (int round = 0; round <= fill_cells; ++round) {
    next = top;
    bool changed = false;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const size_t c = g.index(i, j);
        if (!std::isnan(top[c])) continue;
        next[c] = filled(i, j);
        changed = changed || !std::isnan(next[c]);
      }
    top.swap(next);
    if (!changed) break;
  }
  const float table = static_cast<float>(table_z);
  return build(g, [&](size_t c, std::vector<Span>& out) {
    if (top[c] > table) out.push_back({table, top[c]});
  });
}

}  // namespace rosmill::core::stock
