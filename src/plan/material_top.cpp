#include "rosmill/plan/material_top.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::core {

void MaterialTop::check(const std::string& where) const {
  if (!(cell > 0) || !std::isfinite(cell) || !std::isfinite(x0) || !std::isfinite(y0))
    throw Error(where, "the material grid needs a positive cell and a finite corner");
  const size_t cells = static_cast<size_t>(std::max(nx, 0)) * static_cast<size_t>(std::max(ny, 0));
  if (nx <= 0 || ny <= 0 || top.size() != cells)
    throw Error(where, "the material grid's heights (" + std::to_string(top.size()) + ") do not fill its " +
                           std::to_string(nx) + " x " + std::to_string(ny) + " cells");
  if (!keep.empty() && keep.size() != cells)
    throw Error(where, "the kept cells (" + std::to_string(keep.size()) + ") do not fill the material grid");
  if (!fixture.empty() && fixture.size() != cells)
    throw Error(where, "the fixture's heights (" + std::to_string(fixture.size()) + ") do not fill the material grid");
  if (keep_low.size() != keep_high.size() || (!keep_low.empty() && keep_low.size() != cells))
    throw Error(where, "the kept heights do not fill the material grid");
  if (!cut.empty() && cut.size() != cells)
    throw Error(where, "the heights to cut (" + std::to_string(cut.size()) + ") do not fill the material grid");
}

namespace {

// `values` (nx * ny, or empty) copied into a grid grown by `pad` cells on every side, `fill` around.
template <class T>
void pad_cells(std::vector<T>& values, int nx, int ny, int pad, T fill) {
  if (values.empty()) return;
  const int wide = nx + 2 * pad;
  std::vector<T> grown(static_cast<size_t>(wide) * static_cast<size_t>(ny + 2 * pad), fill);
  for (int j = 0; j < ny; ++j)
    std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(j) * nx, nx,
                grown.begin() + static_cast<std::ptrdiff_t>(j + pad) * wide + pad);
  values.swap(grown);
}

}  // namespace

void MaterialTop::pad(int cells) {
  if (cells <= 0) return;
  pad_cells(top, nx, ny, cells, -INFINITY);
  pad_cells(cut, nx, ny, cells, -INFINITY);
  pad_cells(fixture, nx, ny, cells, -INFINITY);
  pad_cells(keep, nx, ny, cells, uint8_t{0});
  pad_cells(keep_low, nx, ny, cells, NAN);
  pad_cells(keep_high, nx, ny, cells, NAN);
  x0 -= cells * cell;
  y0 -= cells * cell;
  nx += 2 * cells;
  ny += 2 * cells;
}

double MaterialTop::highest() const {
  double h = -INFINITY;
  for (size_t c = 0; c < top.size(); ++c) h = std::max(h, standing(c));
  return h;
}

Box3 MaterialTop::extent() const {
  Box3 b;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const float t = top[static_cast<size_t>(j) * nx + i];
      if (!std::isfinite(t)) continue;
      b.add(Vec3(x0 + i * cell, y0 + j * cell, t));
      b.add(Vec3(x0 + (i + 1) * cell, y0 + (j + 1) * cell, t));
    }
  return b;
}

namespace {

// The highest of `in` within `w` cells of each cell of a row (van Herk and Gil-Werman's running maximum: blocks of
// 2w + 1 cells, the maximum from each block's start and to its end, two lookups a cell).
void running_max(const float* in, int n, int w, float* out, std::vector<float>& ahead, std::vector<float>& behind) {
  const int k = 2 * w + 1;
  ahead.resize(n);
  behind.resize(n);
  for (int b = 0; b < n; b += k) {
    const int e = std::min(n, b + k);
    ahead[b] = in[b];
    for (int i = b + 1; i < e; ++i) ahead[i] = std::max(ahead[i - 1], in[i]);
    behind[e - 1] = in[e - 1];
    for (int i = e - 2; i >= b; --i) behind[i] = std::max(behind[i + 1], in[i]);
  }
  for (int i = 0; i < n; ++i) {
    const int lo = std::max(0, i - w), hi = std::min(n - 1, i + w);
    out[i] = lo / k == hi / k ? *std::max_element(in + lo, in + hi + 1) : std::max(behind[lo], ahead[hi]);
  }
}

}  // namespace

MaterialTop MaterialTop::highest_within(double reach) const {
  const double r = reach / cell + M_SQRT1_2;  // in cells
  const int pad = static_cast<int>(std::ceil(r)) + 1;
  MaterialTop out;
  out.cell = cell;
  out.x0 = x0 - pad * cell;
  out.y0 = y0 - pad * cell;
  out.nx = nx + 2 * pad;
  out.ny = ny + 2 * pad;
  std::vector<float> standing(size_t(out.nx) * out.ny, -INFINITY);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      standing[size_t(j + pad) * out.nx + (i + pad)] = static_cast<float>(this->standing(size_t(j) * nx + i));
  out.top.assign(standing.size(), -INFINITY);
  std::vector<float> row(out.nx), ahead, behind;
  const int rows = static_cast<int>(std::ceil(r));
  for (int dy = -rows; dy <= rows; ++dy) {
    const int w = static_cast<int>(std::floor(std::sqrt(std::max(0.0, r * r - double(dy) * dy))));
    for (int j = 0; j < out.ny; ++j) {
      const int src = j + dy;
      if (src < 0 || src >= out.ny) continue;
      running_max(standing.data() + size_t(src) * out.nx, out.nx, w, row.data(), ahead, behind);
      float* o = out.top.data() + size_t(j) * out.nx;
      for (int i = 0; i < out.nx; ++i) o[i] = std::max(o[i], row[i]);
    }
  }
  return out;
}

double MaterialTop::top_at(const Vec2& p) const {
  const double fi = std::floor((p.x() - x0) / cell), fj = std::floor((p.y() - y0) / cell);
  if (!(fi >= 0 && fj >= 0 && fi < nx && fj < ny)) return -INFINITY;
  return top[size_t(fj) * nx + size_t(fi)];
}

double MaterialTop::highest_along(const Vec2& a, const Vec2& b, double radius) const {
  double h = -INFINITY;
  cells_near(a, b, radius + cell, [&](size_t c, double) { h = std::max(h, standing(c)); });
  return h;
}

double MaterialTop::highest_cut_under(const Vec2& p, double radius) const {
  const std::vector<float>& heights = cut.empty() ? top : cut;
  double h = -INFINITY;
  cells_near(p, p, radius + cell, [&](size_t c, double) { h = std::max(h, double(heights[c])); });
  return h;
}

bool MaterialTop::keep_near(const Vec2& p, double radius, double z, double below, double above) const {
  bool found = false;
  if (keep.empty()) return false;
  const bool any_height = keep_low.empty() || std::isnan(z);
  cells_near(p, p, radius, [&](size_t c, double) {
    found = found || (keep[c] && (any_height || (keep_high[c] >= z - below && keep_low[c] <= z + above)));
  });
  return found;
}

}  // namespace rosmill::core
