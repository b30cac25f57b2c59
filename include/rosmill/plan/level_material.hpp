// The material one roughing level still has to cut, as a bitmap of square cells in XY: a cell is material while
// its centre lies in the region to clear and no cutter disc that passed at this level covered it; air where nothing
// stood or a cutter disc passed; other cells (the part, what no cutter reaches) are neither. The adaptive strategy
// asks it the cutter's radial engagement (the angle of its leading half-circle in material), whether a disc is free
// of material, and where material borders air; it is the planner's own bookkeeping, not the verifier's independent
// measurement.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rosmill/geometry/clip_region.hpp"

namespace rosmill::core {

class LevelMaterial {
 public:
  static constexpr uint8_t kOther = 0, kMaterial = 1, kAir = 2;

  // Cells of edge `cell` covering [lo, hi], no material anywhere: a new map in the memory this one holds (fresh
  // pages cost more than the work on them).
  void reset(const Vec2& lo, const Vec2& hi, double cell);
  // Cells whose centre lies inside the region (even-odd over its loops) become `value`.
  void fill(const clip::Paths& region, uint8_t value);
  bool material(const Vec2& p) const {
    const long i = static_cast<long>(std::floor((p.x() - x0_) / cell_));
    const long j = static_cast<long>(std::floor((p.y() - y0_) / cell_));
    return i >= 0 && j >= 0 && i < nx_ && j < ny_ && bits_[size_t(j) * nx_ + i] == kMaterial;
  }
  // Degrees of the leading half-circle (the half ahead of `dir`) of radius r around p that lies in material:
  // 180 for a full slot, acos(1 - ae / r) for a side cut of width ae, 0 in air.
  double engagement(const Vec2& p, const Vec2& dir, double r) const;
  // engagement(p, dir, r) > deg, counting only as far as it takes.
  bool engaged_over(const Vec2& p, const Vec2& dir, double r, double deg) const;
  // False only when no material lies within r of p (blocks of cells counted: a quick test before finer ones).
  bool near_material(const Vec2& p, double r) const;
  // No material cell centre within r of p.
  bool disc_clear(const Vec2& p, double r) const;
  // No material cell centre within r of the segment a-b.
  bool capsule_clear(const Vec2& a, const Vec2& b, double r) const;
  // Every material cell whose centre lies within r of the segment a-b is cut (becomes air).
  void cut_along(const Vec2& a, const Vec2& b, double r);
  // The same for a cutter that moves from a to b, its disc at a cut already (when it got there): only the cells
  // ahead of that disc are visited.
  void cut_ahead(const Vec2& a, const Vec2& b, double r);
  // The material cells cut_ahead(a, b, r) would cut, into `cells`; whether there are any. cut_cells cuts them.
  bool material_ahead(const Vec2& a, const Vec2& b, double r, std::vector<size_t>& cells) const;
  void cut_cells(const std::vector<size_t>& cells);
  double material_area() const;
  // While a log is set, every material cell cut is added to it; restore() makes them material again.
  void log_cuts(std::vector<size_t>* log) { log_ = log; }
  void restore(const std::vector<size_t>& log) {
    for (size_t c : log) set(c, kMaterial);
  }
  // The area of the material cells with no other cell (neither material nor air: the walls' side) within
  // `margin` cells: what is left off the walls, without the skin a cutter's chords leave on them.
  double material_area_off_walls(long margin) const;
  // Those cells, grouped into islands joined across edges.
  std::vector<std::vector<size_t>> islands_off_walls(long margin) const;
  double cell() const { return cell_; }
  // Whether the half-circle's samples are counted with AVX2 (where the processor has it; the same counts as the
  // scalar path, which tests check by switching it off). use_vector_arcs returns whether it is now on.
  static bool vector_arcs();
  static bool use_vector_arcs(bool on);

  // Cells by index (row after row), for maps of the same grid.
  long nx() const { return nx_; }
  long ny() const { return ny_; }
  uint8_t value(size_t c) const { return bits_[c]; }
  const uint8_t* values() const { return bits_.data(); }  // nx() * ny() of them
  Vec2 centre(size_t c) const {
    const long j = row_of(c);
    return {x0_ + (double(long(c) - j * nx_) + 0.5) * cell_, y0_ + (double(j) + 0.5) * cell_};
  }
  // The row of cell c (c / nx) without a division, which costs tens of cycles on the paths that ask it per cell:
  // by the reciprocal, then one step either way where its rounding fell across a row's end.
  long row_of(size_t c) const {
    long j = static_cast<long>(double(c) * per_nx_);
    j -= long(size_t(j) * size_t(nx_) > c);
    j += long(size_t(j + 1) * size_t(nx_) <= c);
    return j;
  }
  // Blocks of cells, for searches outward from a point: the block holding p (clamped to the grid), how many
  // blocks there are each way, the edge length of one.
  void block_of(const Vec2& p, long& bi, long& bj) const;
  long blocks_x() const { return bx_; }
  long blocks_y() const { return by_; }
  double block_span() const { return kBlock * cell_; }
  // Calls f(cell, centre, normal) for each material cell of block (bi, bj) that borders air among its eight
  // neighbours and that skip(cell) does not pass over; `normal` is the unit direction from the cell toward the air
  // around it (within two cells).
  template <class Skip, class F>
  void edge_cells(long bi, long bj, const Skip& skip, const F& f) const;

 private:
  // No other cell within `margin` cells of cell (i, j).
  bool off_walls(long i, long j, long margin) const;
  // Samples of the leading half-circle in material, counted up to `enough`; with `decide`, only as far as it
  // takes to tell whether `enough` are in (the count returned is then below it exactly when fewer are).
  int arc_in(const Vec2& p, const Vec2& dir, double r, int enough, bool decide) const;
  // Calls f(cell) for the cells whose centre lies within r of the segment a-b but not within r of a, row by row
  // (the capsule's span of each row less the disc's), until f returns false.
  template <class F>
  bool each_ahead(const Vec2& a, const Vec2& b, double r, const F& f) const;
  // Calls f(cell index) for the cells whose centre lies within r of the segment a-b until f returns false.
  template <class F>
  bool each_within(const Vec2& a, const Vec2& b, double r, const F& f) const;
  double x0_ = 0, y0_ = 0, cell_ = 1;
  long nx_ = 0, ny_ = 0;
  double per_nx_ = 1;  // 1 / nx_
  bool index32_ = true;  // every cell's index fits 32 bits (the half-circle's fast path indexes in 32 bits)
  std::vector<uint8_t> bits_;
  // Material cells per block of kBlock x kBlock cells.
  static constexpr long kBlock = 16;
  // 1 / |(di, dj)| over a 5 x 5 window (0 at its centre).
  static constexpr double kR1 = 1.0, kR2 = 0.7071067811865476, kR4 = 0.5, kR5 = 0.4472135954999579,
                          kR8 = 0.3535533905932738;
  static constexpr double kInverse[5][5] = {{kR8, kR5, kR4, kR5, kR8},
                                            {kR5, kR2, kR1, kR2, kR5},
                                            {kR4, kR1, 0.0, kR1, kR4},
                                            {kR5, kR2, kR1, kR2, kR5},
                                            {kR8, kR5, kR4, kR5, kR8}};
  long bx_ = 0, by_ = 0;
  std::vector<uint32_t> block_count_;
  std::vector<uint32_t> block_air_;  // air cells per block
  // Air in block (bi, bj) or one of the blocks around it: else no cell of the block borders air.
  bool air_near_block(long bi, long bj) const;
  // Of the kBlock cells of row j from column i (all, and their neighbours, on the grid): bit k set when cell
  // i + k is material with air among its eight neighbours. Sixteen cells at once in SSE2 registers.
  uint32_t edge_row(long j, long i) const;
  std::vector<double> crossings_;  // fill's scan-line crossings, row after row
  std::vector<size_t>* log_ = nullptr;
  void set(size_t c, uint8_t value);
  // Cells i0 ... i1 of row j.
  void set_run(long j, long i0, long i1, uint8_t value);
};

template <class Skip, class F>
void LevelMaterial::edge_cells(long bi, long bj, const Skip& skip, const F& f) const {
  if (bi < 0 || bj < 0 || bi >= bx_ || bj >= by_ || !block_count_[size_t(bj) * bx_ + bi]) return;
  if (!air_near_block(bi, bj)) return;  // material inside, far from the front
  const long i1 = std::min(nx_, (bi + 1) * kBlock), j1 = std::min(ny_, (bj + 1) * kBlock);
  // A block two cells or more inside the grid's edges (nearly all) reads its cells' neighbours unchecked.
  const bool inner = bi * kBlock >= 2 && bj * kBlock >= 2 && i1 + 2 <= nx_ && j1 + 2 <= ny_;
  const auto air = [&](long i, long j) {
    return (inner || (i >= 0 && j >= 0 && i < nx_ && j < ny_)) && bits_[size_t(j) * nx_ + i] == kAir;
  };
  // Cell (i, j), a material cell that borders air and is not skipped: f with the air around it, each cell
  // weighted by its inverse distance, within two cells.
  const auto edge = [&](long i, long j) {
    const size_t c = size_t(j) * nx_ + i;
    if (skip(c)) return;
    double gx = 0, gy = 0;
    for (long dj = -2; dj <= 2; ++dj)
      for (long di = -2; di <= 2; ++di)
        if (air(i + di, j + dj)) gx += di * kInverse[dj + 2][di + 2], gy += dj * kInverse[dj + 2][di + 2];
    const double len = std::sqrt(gx * gx + gy * gy);
    if (len > 1e-9) f(c, centre(c), Vec2(gx / len, gy / len));
  };
  for (long j = bj * kBlock; j < j1; ++j) {
    if (inner) {  // a whole block's row, its neighbours on the grid
      for (uint32_t bits = edge_row(j, bi * kBlock); bits; bits &= bits - 1)
        edge(bi * kBlock + __builtin_ctz(bits), j);
      continue;
    }
    for (long i = bi * kBlock; i < i1; ++i)
      if (bits_[size_t(j) * nx_ + i] == kMaterial &&
          (air(i - 1, j) || air(i + 1, j) || air(i, j - 1) || air(i, j + 1) || air(i - 1, j - 1) ||
           air(i + 1, j - 1) || air(i - 1, j + 1) || air(i + 1, j + 1)))
        edge(i, j);
  }
}

}  // namespace rosmill::core
