#include "rosmill/plan/level_material.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <utility>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "rosmill/geometry/grid_flood.hpp"
#include "rosmill/geometry/segment_distance.hpp"
#include "rosmill/plan/material_top.hpp"

namespace rosmill::core {
namespace {

// Samples of the leading half-circle: a sample per 2 degrees, each counting for its 2 degrees.
constexpr int kArcSamples = 90;
// The table is padded to a multiple of eight (the samples placed at a time) with copies of the last sample, so
// that the loops placing them on the grid have no scalar tail; the copies are placed, never counted.
constexpr int kArcPadded = 96;

// The sample directions relative to the heading: cos and sin of -90 + (k + 0.5) * 2 degrees.
struct ArcTable {
  double c[kArcPadded], s[kArcPadded];
  ArcTable() {
    for (int k = 0; k < kArcPadded; ++k) {
      const double a = -0.5 * M_PI + (std::min(k, kArcSamples - 1) + 0.5) * M_PI / kArcSamples;
      c[k] = std::cos(a), s[k] = std::sin(a);
    }
  }
};

// The cells under the samples of a half-circle wholly on the grid: centre (px, py) and axes u (ahead), v (left)
// in cell units.
void arc_cells(const ArcTable& t, double px, double py, const Vec2& u, const Vec2& v, int32_t nx, int32_t* cells) {
  const double ux = u.x(), uy = u.y(), vx = v.x(), vy = v.y();
  for (int k = 0; k < kArcPadded; ++k) {
    const double x = px + t.c[k] * ux + t.s[k] * vx, y = py + t.c[k] * uy + t.s[k] * vy;
    cells[k] = static_cast<int32_t>(y) * nx + static_cast<int32_t>(x);
  }
}

// Whether counting stops after the samples [0, k): `enough` in, or, when only the side of `enough` is asked
// (decide), too few left to make it up.
bool arc_decided(int in, int k, int enough, bool decide) {
  return in >= enough || (decide && in + (kArcSamples - k) < enough);
}

// Samples of a half-circle wholly on the grid in material, counted eight at a time with the stops tried between
// (the same count as the scalar path: the same cell indices, the same stops).
int arc_count(const ArcTable& t, double px, double py, const Vec2& u, const Vec2& v, int32_t nx,
              const uint8_t* bits, uint8_t material, int enough, bool decide) {
  int32_t cells[kArcPadded];
  arc_cells(t, px, py, u, v, nx, cells);
  int in = 0;
  for (int k0 = 0; k0 < kArcSamples; k0 += 8) {
    const int k1 = std::min(k0 + 8, kArcSamples);
    for (int k = k0; k < k1; ++k) in += bits[cells[k]] == material;
    if (arc_decided(in, k1, enough, decide)) break;
  }
  return in;
}

#if defined(__x86_64__)
// Cell indices of samples k .. k + 3 (AVX2): the scalar path's operations in its order, no fused multiply-add, so
// the same indices.
__attribute__((target("avx2"))) __m128i arc_cells4(const ArcTable& t, int k, __m256d x0, __m256d y0, __m256d ux,
                                                   __m256d uy, __m256d vx, __m256d vy, __m128i nx) {
  const __m256d c = _mm256_loadu_pd(t.c + k), s = _mm256_loadu_pd(t.s + k);
  const __m256d x = _mm256_add_pd(_mm256_add_pd(x0, _mm256_mul_pd(c, ux)), _mm256_mul_pd(s, vx));
  const __m256d y = _mm256_add_pd(_mm256_add_pd(y0, _mm256_mul_pd(c, uy)), _mm256_mul_pd(s, vy));
  return _mm_add_epi32(_mm_mullo_epi32(_mm256_cvttpd_epi32(y), nx), _mm256_cvttpd_epi32(x));
}

// arc_count with AVX2: eight samples placed at a time, their cells gathered at once (four bytes from each index:
// the grid keeps three bytes of padding), and only as many eights placed as the count needs. The hottest loop of
// adaptive clearing.
__attribute__((target("avx2,popcnt"))) int arc_count_avx2(const ArcTable& t, double px, double py, const Vec2& u,
                                                            const Vec2& v, int32_t nx, const uint8_t* bits,
                                                            uint8_t material, int enough, bool decide) {
  const __m256d ux = _mm256_set1_pd(u.x()), uy = _mm256_set1_pd(u.y()), vx = _mm256_set1_pd(v.x()),
                vy = _mm256_set1_pd(v.y()), x0 = _mm256_set1_pd(px), y0 = _mm256_set1_pd(py);
  const __m128i row = _mm_set1_epi32(nx);
  const __m256i low_byte = _mm256_set1_epi32(0xff), want = _mm256_set1_epi32(material);
  int in = 0;
  for (int k0 = 0; k0 < kArcSamples; k0 += 8) {
    const __m256i cell = _mm256_set_m128i(arc_cells4(t, k0 + 4, x0, y0, ux, uy, vx, vy, row),
                                          arc_cells4(t, k0, x0, y0, ux, uy, vx, vy, row));
    const __m256i got = _mm256_i32gather_epi32(reinterpret_cast<const int*>(bits), cell, 1);
    const __m256i is = _mm256_cmpeq_epi32(_mm256_and_si256(got, low_byte), want);
    const int k1 = std::min(k0 + 8, kArcSamples);
    const unsigned counted = (1u << (k1 - k0)) - 1;  // the padded samples past kArcSamples are not counted
    in += __builtin_popcount(unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(is))) & counted);
    if (arc_decided(in, k1, enough, decide)) break;
  }
  return in;
}
#endif

bool cpu_runs_vector_arcs() {
#if defined(__x86_64__)
  static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
  return yes;
#else
  return false;
#endif
}

bool& vector_arcs_flag() {
  static bool on = cpu_runs_vector_arcs();
  return on;
}

// The count of a half-circle wholly on the grid, by the widest path the processor runs.
int arc_count_on_grid(const ArcTable& t, double px, double py, const Vec2& u, const Vec2& v, int32_t nx,
                      const uint8_t* bits, uint8_t material, int enough, bool decide) {
#if defined(__x86_64__)
  if (vector_arcs_flag()) return arc_count_avx2(t, px, py, u, v, nx, bits, material, enough, decide);
#endif
  return arc_count(t, px, py, u, v, nx, bits, material, enough, decide);
}

// Cell and block indices from coordinates in cell units, clamped as the loops over them need, without the library's
// floor and ceil (calls on x86-64 below SSE4.1, in the hottest loops here); NaN falls to the low side.
// max(0, ceil(x)), at most `past` (an index no loop reaches): the first index of a run.
long first_index(double x, long past) {
  if (!(x > 0)) return 0;
  if (x >= double(past)) return past;
  const long i = static_cast<long>(x);
  return i + (double(i) < x);
}
// max(0, floor(x)), at most `past`.
long low_index(double x, long past) {
  if (!(x >= 0)) return 0;
  return x >= double(past) ? past : static_cast<long>(x);
}
// min(last, floor(x)); -1 (before any index) below 0: the last index of a run.
long last_index(double x, long last) {
  if (!(x >= 0)) return -1;
  return x >= double(last) ? last : static_cast<long>(x);
}

}  // namespace

void LevelMaterial::reset(const Vec2& lo, const Vec2& hi, double cell) {
  x0_ = lo.x(), y0_ = lo.y(), cell_ = cell;
  nx_ = std::max(1L, static_cast<long>(std::ceil((hi.x() - lo.x()) / cell)));
  ny_ = std::max(1L, static_cast<long>(std::ceil((hi.y() - lo.y()) / cell)));
  per_nx_ = 1.0 / double(nx_);
  // Three bytes past the last cell: the half-circle's gather reads four bytes from a cell's index.
  bits_.assign(size_t(nx_) * size_t(ny_) + 3, 0);
  bx_ = (nx_ + kBlock - 1) / kBlock, by_ = (ny_ + kBlock - 1) / kBlock;
  block_count_.assign(size_t(bx_) * size_t(by_), 0);
  block_air_.assign(size_t(bx_) * size_t(by_), 0);
  index32_ = nx_ * ny_ <= long(INT32_MAX);
}

void LevelMaterial::set(size_t c, uint8_t value) {
  const long j = row_of(c), i = long(c) - j * nx_;
  set_run(j, i, i, value);
}

void LevelMaterial::set_run(long j, long i0, long i1, uint8_t value) {
  const size_t row = size_t(j) * size_t(nx_);
  uint32_t* const material = &block_count_[size_t(j / kBlock) * size_t(bx_)];
  uint32_t* const air = &block_air_[size_t(j / kBlock) * size_t(bx_)];
  // Counts of unsigned words: adding -n as its two's complement takes n away.
  if (log_) {  // each material cell cut is logged
    for (long i = i0; i <= i1; ++i) {
      const uint8_t old = bits_[row + size_t(i)];
      if (old == value) continue;
      if (old == kMaterial) log_->push_back(row + size_t(i));
      bits_[row + size_t(i)] = value;
      material[i / kBlock] += uint32_t(value == kMaterial) - uint32_t(old == kMaterial);
      air[i / kBlock] += uint32_t(value == kAir) - uint32_t(old == kAir);
    }
    return;
  }
  // A block's part of the run at once: what its cells held counted (vectorised), then all set.
  for (long s = i0; s <= i1;) {
    const long e = std::min(i1, (s / kBlock + 1) * kBlock - 1);
    uint8_t* const cells = &bits_[row + size_t(s)];
    const uint32_t n = uint32_t(e - s + 1);
    uint32_t was_material = 0, was_air = 0;
    for (uint32_t k = 0; k < n; ++k) was_material += cells[k] == kMaterial, was_air += cells[k] == kAir;
    std::memset(cells, value, n);
    material[s / kBlock] += uint32_t(value == kMaterial) * n - was_material;
    air[s / kBlock] += uint32_t(value == kAir) * n - was_air;
    s = e + 1;
  }
}

bool LevelMaterial::air_near_block(long bi, long bj) const {
  for (long j = std::max(0L, bj - 1); j <= std::min(by_ - 1, bj + 1); ++j)
    for (long i = std::max(0L, bi - 1); i <= std::min(bx_ - 1, bi + 1); ++i)
      if (block_air_[size_t(j) * bx_ + i]) return true;
  return false;
}

uint32_t LevelMaterial::edge_row(long j, long i) const {
  const uint8_t* const at = &bits_[size_t(j) * size_t(nx_) + size_t(i)];
  const ptrdiff_t up = -ptrdiff_t(nx_), down = ptrdiff_t(nx_);
#if defined(__x86_64__)
  static_assert(kBlock == 16, "a block's row is one SSE2 register of cells");
  const __m128i air = _mm_set1_epi8(char(kAir));
  const auto is_air = [&](ptrdiff_t offset) {
    return _mm_cmpeq_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(at + offset)), air);
  };
  const __m128i near = _mm_or_si128(
      _mm_or_si128(_mm_or_si128(is_air(up - 1), is_air(up)), _mm_or_si128(is_air(up + 1), is_air(-1))),
      _mm_or_si128(_mm_or_si128(is_air(1), is_air(down - 1)), _mm_or_si128(is_air(down), is_air(down + 1))));
  const __m128i material =
      _mm_cmpeq_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(at)), _mm_set1_epi8(char(kMaterial)));
  return uint32_t(_mm_movemask_epi8(_mm_and_si128(near, material)));
#else
  uint32_t bits = 0;
  for (long k = 0; k < kBlock; ++k) {
    const uint8_t* c = at + k;
    const bool near = c[up - 1] == kAir || c[up] == kAir || c[up + 1] == kAir || c[-1] == kAir || c[1] == kAir ||
                      c[down - 1] == kAir || c[down] == kAir || c[down + 1] == kAir;
    bits |= uint32_t(*c == kMaterial && near) << k;
  }
  return bits;
#endif
}

void LevelMaterial::block_of(const Vec2& p, long& bi, long& bj) const {
  bi = std::clamp(static_cast<long>(std::floor((p.x() - x0_) / block_span())), 0L, bx_ - 1);
  bj = std::clamp(static_cast<long>(std::floor((p.y() - y0_) / block_span())), 0L, by_ - 1);
}

bool LevelMaterial::near_material(const Vec2& p, double r) const {
  const double span = kBlock * cell_;
  const long i0 = low_index((p.x() - r - x0_) / span, bx_), i1 = last_index((p.x() + r - x0_) / span, bx_ - 1);
  const long j0 = low_index((p.y() - r - y0_) / span, by_), j1 = last_index((p.y() + r - y0_) / span, by_ - 1);
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i)
      if (block_count_[size_t(j) * bx_ + i]) return true;
  return false;
}

void LevelMaterial::fill(const clip::Paths& region, uint8_t value) {
  // Scan lines through the cell centres. Each loop edge adds its crossings to the rows it spans (counted first,
  // then placed: work by the edges' length, not rows times edges); each row's crossings, sorted, bound the runs
  // inside.
  const auto each_crossing = [&](const auto& f) {
    for (const clip::Path& path : region)
      for (size_t k = 0; k < path.size(); ++k) {
        const Vec2 a = clip::from_point(path[k]), b = clip::from_point(path[(k + 1) % path.size()]);
        const double lo = std::min(a.y(), b.y()), hi = std::max(a.y(), b.y());
        const long j0 = std::max(0L, static_cast<long>(std::floor((lo - y0_) / cell_ - 0.5)));
        const long j1 = std::min(ny_ - 1, static_cast<long>(std::ceil((hi - y0_) / cell_ - 0.5)));
        for (long j = j0; j <= j1; ++j) {
          const double y = y0_ + (j + 0.5) * cell_;
          if ((a.y() <= y) != (b.y() <= y)) f(j, a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
        }
      }
  };
  std::vector<size_t> start(size_t(ny_) + 1, 0);
  each_crossing([&](long j, double) { ++start[j + 1]; });
  for (long j = 0; j < ny_; ++j) start[j + 1] += start[j];
  crossings_.resize(start[ny_]);
  std::vector<size_t> next(start.begin(), start.end() - 1);
  each_crossing([&](long j, double x) { crossings_[next[j]++] = x; });
  for (long j = 0; j < ny_; ++j) {
    const auto first = crossings_.begin() + start[j], last = crossings_.begin() + start[j + 1];
    std::sort(first, last);
    for (auto k = first; k + 1 < last; k += 2) {
      const long i0 = std::max(0L, static_cast<long>(std::ceil((*k - x0_) / cell_ - 0.5)));
      const long i1 = std::min(nx_ - 1, static_cast<long>(std::floor((*(k + 1) - x0_) / cell_ - 0.5)));
      set_run(j, i0, i1, value);
    }
  }
}

bool LevelMaterial::vector_arcs() { return vector_arcs_flag(); }

bool LevelMaterial::use_vector_arcs(bool on) { return vector_arcs_flag() = on && cpu_runs_vector_arcs(); }

int LevelMaterial::arc_in(const Vec2& p, const Vec2& dir, double r, int enough, bool decide) const {
  if (!near_material(p, r)) return 0;
  static const ArcTable table;
  // In cell units from the grid's corner; a sample off the grid is no material.
  const Vec2 u = dir.normalized() * (r / cell_), v(-u.y(), u.x());
  const double px = (p.x() - x0_) / cell_, py = (p.y() - y0_) / cell_;
  // Counting stops once `enough` are in, and, when only the side of `enough` is asked (decide), once the
  // samples left cannot make up the difference.
  const double reach = r / cell_ + 1;
  if (index32_ && px >= reach && py >= reach && px + reach < double(nx_) && py + reach < double(ny_))
    // The whole half-circle on the grid (the cutter inside the region a level works in): no test per sample.
    return arc_count_on_grid(table, px, py, u, v, static_cast<int32_t>(nx_), bits_.data(), kMaterial, enough, decide);
  int in = 0;
  for (int k = 0; k < kArcSamples; ++k) {
    const double x = px + table.c[k] * u.x() + table.s[k] * v.x(), y = py + table.c[k] * u.y() + table.s[k] * v.y();
    const bool on = x >= 0 && y >= 0 && x < double(nx_) && y < double(ny_);
    in += on && bits_[size_t(static_cast<long>(y)) * nx_ + static_cast<long>(x)] == kMaterial;
    if (arc_decided(in, k + 1, enough, decide)) break;
  }
  return in;
}

double LevelMaterial::engagement(const Vec2& p, const Vec2& dir, double r) const {
  return 180.0 * arc_in(p, dir, r, kArcSamples, false) / kArcSamples;
}

bool LevelMaterial::engaged_over(const Vec2& p, const Vec2& dir, double r, double deg) const {
  // Over deg once more than deg / (180 / kArcSamples) samples are in.
  const int most = static_cast<int>(std::floor(deg * kArcSamples / 180.0));
  return arc_in(p, dir, r, most + 1, true) > most;
}

bool LevelMaterial::disc_clear(const Vec2& p, double r) const { return capsule_clear(p, p, r); }

template <class F>
bool LevelMaterial::each_within(const Vec2& a, const Vec2& b, double r, const F& f) const {
  const long i0 = low_index((std::min(a.x(), b.x()) - r - x0_) / cell_, nx_);
  const long i1 = last_index((std::max(a.x(), b.x()) + r - x0_) / cell_, nx_ - 1);
  const long j0 = low_index((std::min(a.y(), b.y()) - r - y0_) / cell_, ny_);
  const long j1 = last_index((std::max(a.y(), b.y()) + r - y0_) / cell_, ny_ - 1);
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i) {
      const size_t c = size_t(j) * nx_ + i;
      if (bits_[c] != kMaterial) continue;
      if (segment_distance(Vec2(x0_ + (i + 0.5) * cell_, y0_ + (j + 0.5) * cell_), a, b) <= r && !f(c))
        return false;
    }
  return true;
}

bool LevelMaterial::capsule_clear(const Vec2& a, const Vec2& b, double r) const {
  if (!near_material(a, r + (b - a).norm())) return true;
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / std::max(r, cell_))));
  for (int k = 0; k < n; ++k)
    if (!each_within(a + (b - a) * (double(k) / n), a + (b - a) * (double(k + 1) / n), r,
                     [](size_t) { return false; }))
      return false;
  return true;
}

void LevelMaterial::cut_along(const Vec2& a, const Vec2& b, double r) {
  // In pieces no longer than r: the cells visited are those of each piece's box, about the swept area.
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / std::max(r, cell_))));
  for (int k = 0; k < n; ++k)
    each_within(a + (b - a) * (double(k) / n), a + (b - a) * (double(k + 1) / n), r, [&](size_t c) {
      set(c, kAir);
      return true;
    });
}

template <class F>
bool LevelMaterial::each_ahead(const Vec2& a, const Vec2& b, double r, const F& f) const {
  const Vec2 d = b - a;
  const double len = d.norm();
  const Vec2 u = len > 1e-12 ? Vec2(d / len) : Vec2::UnitX(), n(-u.y(), u.x());
  const long j0 = first_index((std::min(a.y(), b.y()) - r - y0_) / cell_ - 0.5, ny_);
  const long j1 = last_index((std::max(a.y(), b.y()) + r - y0_) / cell_ - 0.5, ny_ - 1);
  // The span of a disc of radius r at c on the row at y (empty: lo > hi).
  const auto disc = [&](const Vec2& c, double y, double& lo, double& hi) {
    const double h = r * r - (y - c.y()) * (y - c.y());
    lo = h < 0 ? INFINITY : c.x() - std::sqrt(h);
    hi = h < 0 ? -INFINITY : c.x() + std::sqrt(h);
  };
  // The band's long sides, o + t d, and the reciprocals the rows use (a product per row, not a division).
  const bool band = len > 1e-12 && std::abs(u.y()) > 1e-12;
  const Vec2 sides[2] = {a - r * n, a + r * n};
  const double per_dy = band ? 1 / d.y() : 0, per_cell = 1 / cell_;
  // Row j's cells: false once f returns false.
  const auto row = [&](long j) {
    const double y = y0_ + (j + 0.5) * cell_;
    // The capsule's span: its two end discs and the band between them, a convex union, so their hull.
    double alo, ahi, blo, bhi;
    disc(a, y, alo, ahi);
    disc(b, y, blo, bhi);
    double lo = std::min(alo, blo), hi = std::max(ahi, bhi);
    if (band) {
      // The band: points a + t d + s n with t in [0, 1], |s| <= r; on this row it spans between the crossings
      // of its four sides.
      for (const Vec2& o : sides) {
        const double t = (y - o.y()) * per_dy;
        if (t >= 0 && t <= 1) lo = std::min(lo, o.x() + t * d.x()), hi = std::max(hi, o.x() + t * d.x());
      }
    } else if (len > 1e-12 && std::abs(y - a.y()) <= r) {
      lo = std::min(lo, std::min(a.x(), b.x())), hi = std::max(hi, std::max(a.x(), b.x()));
    }
    if (lo > hi) return true;
    // The row's cells in [lo, hi] but not in [alo, ahi]: the runs on either side of a's disc.
    const long i0 = first_index((lo - x0_) * per_cell - 0.5, nx_);
    const long i1 = last_index((hi - x0_) * per_cell - 0.5, nx_ - 1);
    const size_t at = size_t(j) * nx_;
    if (alo > ahi) {  // a's disc misses the row
      for (long i = i0; i <= i1; ++i)
        if (bits_[at + i] == kMaterial && !f(at + i)) return false;
      return true;
    }
    const long ai0 = first_index((alo - x0_) * per_cell - 0.5, nx_);
    const long ai1 = last_index((ahi - x0_) * per_cell - 0.5, nx_ - 1);
    for (long i = i0; i <= std::min(i1, ai0 - 1); ++i)
      if (bits_[at + i] == kMaterial && !f(at + i)) return false;
    for (long i = std::max(i0, ai1 + 1); i <= i1; ++i)
      if (bits_[at + i] == kMaterial && !f(at + i)) return false;
    return true;
  };
  for (long j = j0; j <= j1; ++j)
    if (!row(j)) return false;
  return true;
}

void LevelMaterial::cut_ahead(const Vec2& a, const Vec2& b, double r) {
  each_ahead(a, b, r, [&](size_t c) {
    set(c, kAir);
    return true;
  });
}

bool LevelMaterial::material_ahead(const Vec2& a, const Vec2& b, double r, std::vector<size_t>& cells) const {
  cells.clear();
  if (!near_material(b, r + (b - a).norm())) return false;
  each_ahead(a, b, r, [&](size_t c) {
    cells.push_back(c);
    return true;
  });
  return !cells.empty();
}

void LevelMaterial::cut_cells(const std::vector<size_t>& cells) {
  for (size_t c : cells) set(c, kAir);
}

double LevelMaterial::material_area() const {
  size_t n = 0;
  for (uint32_t c : block_count_) n += c;
  return double(n) * cell_ * cell_;
}

bool LevelMaterial::off_walls(long i, long j, long margin) const {
  for (long dj = -margin; dj <= margin; ++dj)
    for (long di = -margin; di <= margin; ++di) {
      const long ii = i + di, jj = j + dj;
      if (ii >= 0 && jj >= 0 && ii < nx_ && jj < ny_ && bits_[size_t(jj) * nx_ + ii] == kOther) return false;
    }
  return true;
}

double LevelMaterial::material_area_off_walls(long margin) const {
  size_t n = 0;
  for (long bj = 0; bj < by_; ++bj)
    for (long bi = 0; bi < bx_; ++bi) {
      if (!block_count_[size_t(bj) * bx_ + bi]) continue;  // no material in the block
      for (long j = bj * kBlock; j < std::min(ny_, (bj + 1) * kBlock); ++j)
        for (long i = bi * kBlock; i < std::min(nx_, (bi + 1) * kBlock); ++i)
          n += bits_[size_t(j) * nx_ + i] == kMaterial && off_walls(i, j, margin);
    }
  return double(n) * cell_ * cell_;
}

std::vector<std::vector<size_t>> LevelMaterial::islands_off_walls(long margin) const {
  std::vector<std::vector<size_t>> islands;
  const size_t n = size_t(nx_) * size_t(ny_);
  std::vector<uint8_t> seen(n, 0);
  std::vector<size_t> open;
  const auto in = [&](size_t c) {
    const long j = row_of(c);
    return bits_[c] == kMaterial && off_walls(long(c) - j * nx_, j, margin);
  };
  for (size_t c = 0; c < n; ++c) {
    if (seen[c] || !in(c)) continue;
    std::vector<size_t> island;
    flood_cells(nx_, ny_, c, seen, open, in, [&](size_t k) { island.push_back(k); });
    islands.push_back(std::move(island));
  }
  return islands;
}

}  // namespace rosmill::core
