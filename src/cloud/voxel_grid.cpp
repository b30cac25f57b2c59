#include "rosmill/cloud/voxel_grid.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"

namespace rosmill::core {
namespace {

// The cloud's box; throws Error on a point that is not finite (no float-to-integer cast of a NaN below).
Box3 bounds(const std::vector<Vec3>& points) {
  std::atomic<bool> finite{true};
  const Box3 box = reduce_pieces(
      size_t(0), points.size(), size_t(1) << 14, Box3(),
      [&](size_t begin, size_t end, Box3 part) {
        for (size_t i = begin; i != end; ++i)
          if (points[i].allFinite())
            part.add(points[i]);
          else
            finite = false;
        return part;
      },
      [](Box3 a, const Box3& b) {
        a.add(b);
        return a;
      });
  if (!finite) throw Error("voxel grid", "a point is not finite");
  return box;
}

// A point's cell and its index. Clouds whose grid has at most 2^32 cells (nearly all) sort 8-byte records instead
// of 16: half the memory traffic of every pass.
template <class Key>
struct Keyed {
  Key cell;
  uint32_t index;
};

struct Grid {
  Vec3 origin;
  double inverse;  // 1 / leaf
  uint64_t nx, ny, nz;
  int bits;  // of the largest key
};

// Sorts by cell, keeping the points' order within a cell: a least-significant-digit radix sort over the key's
// `bits`, each pass counted and scattered by chunks on every core. The chunks are fixed, so the result is the same
// whatever the number of threads. A comparison sort of a few million keys took longer than the rest of the filter.
template <class Key>
void sort_by_cell(std::vector<Keyed<Key>>& keyed, int bits) {
  constexpr int kDigit = 11;
  constexpr size_t kBuckets = size_t(1) << kDigit;
  const size_t n = keyed.size();
  const size_t chunks = std::clamp<size_t>(n / 65536, 1, 16);
  std::vector<std::array<size_t, kBuckets>> offsets(chunks);
  std::vector<Keyed<Key>> scattered(n);
  const auto chunk_range = [&](size_t c) { return std::pair<size_t, size_t>(c * n / chunks, (c + 1) * n / chunks); };
  for (int shift = 0; shift < bits; shift += kDigit) {
    const auto digit = [&](const Keyed<Key>& k) { return size_t(k.cell >> shift) & (kBuckets - 1); };
    for_each_index(size_t(0), chunks, [&](size_t c) {
      offsets[c].fill(0);
      const auto [begin, end] = chunk_range(c);
      for (size_t i = begin; i < end; ++i) ++offsets[c][digit(keyed[i])];
    });
    size_t sum = 0;  // bucket by bucket, chunk by chunk: a stable order
    for (size_t b = 0; b < kBuckets; ++b)
      for (size_t c = 0; c < chunks; ++c) sum += std::exchange(offsets[c][b], sum);
    for_each_index(size_t(0), chunks, [&](size_t c) {
      const auto [begin, end] = chunk_range(c);
      for (size_t i = begin; i < end; ++i) scattered[offsets[c][digit(keyed[i])]++] = keyed[i];
    });
    keyed.swap(scattered);
  }
}

// The cells' keys, sorted; then the centroid of each run of one cell.
template <class Key>
std::vector<Vec3> cell_centroids(const std::vector<Vec3>& points, const Grid& g) {
  std::vector<Keyed<Key>> keyed(points.size());
  for_each_piece<size_t>(0, points.size(), 1 << 14, [&](size_t begin, size_t end) {
    for (size_t i = begin; i != end; ++i) {
      const Vec3 c = ((points[i] - g.origin) * g.inverse).array().floor();
      // The largest coordinate may round up to the cell past the end: it belongs to the last one.
      const uint64_t x = std::min(uint64_t(c.x()), g.nx - 1), y = std::min(uint64_t(c.y()), g.ny - 1),
                     z = std::min(uint64_t(c.z()), g.nz - 1);
      keyed[i] = {Key(x + g.nx * (y + g.ny * z)), uint32_t(i)};
    }
  });
  sort_by_cell(keyed, g.bits);
  std::vector<size_t> starts;  // where each occupied cell's run begins
  for (size_t i = 0; i < keyed.size(); ++i)
    if (i == 0 || keyed[i].cell != keyed[i - 1].cell) starts.push_back(i);
  starts.push_back(keyed.size());
  std::vector<Vec3> out(starts.size() - 1);
  for_each_piece<size_t>(0, out.size(), 4096, [&](size_t begin, size_t end) {
    for (size_t c = begin; c != end; ++c) {
      Vec3 sum = Vec3::Zero();  // relative to the corner: millimetre clouds far from their origin keep precision
      for (size_t k = starts[c]; k < starts[c + 1]; ++k) sum += points[keyed[k].index] - g.origin;
      out[c] = g.origin + sum / double(starts[c + 1] - starts[c]);
    }
  });
  return out;
}

}  // namespace

std::vector<Vec3> voxel_centroids(const std::vector<Vec3>& points, double leaf) {
  if (!(leaf > 0) || !std::isfinite(leaf)) throw Error("voxel grid", "the leaf must be a positive number of mm");
  if (points.empty()) return {};
  if (points.size() > UINT32_MAX) throw Error("voxel grid", "more than 2^32 points");
  const Box3 box = bounds(points);
  // Cells per axis; the key x + nx (y + ny z) orders the cells as PCL does.
  const Vec3 n = (box.size() / leaf).array().floor() + 1;
  if (!(n.x() * n.y() * n.z() < 0x1p62))
    throw Error("voxel grid", "leaf size " + std::to_string(leaf) + " mm is too small for a cloud of this extent");
  Grid g{box.min, 1 / leaf, uint64_t(n.x()), uint64_t(n.y()), uint64_t(n.z()), 0};
  const uint64_t largest = g.nx * g.ny * g.nz - 1;
  while (g.bits < 64 && (largest >> g.bits) != 0) ++g.bits;
  return g.bits <= 32 ? cell_centroids<uint32_t>(points, g) : cell_centroids<uint64_t>(points, g);
}

}  // namespace rosmill::core
