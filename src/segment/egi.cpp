// Near-equal-area direction bins and the per-patch Extended Gaussian Images.
#include "rosmill/segment/egi.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"

namespace rosmill::core::segment {
namespace {

Vec3 direction(double polar, double azimuth) {
  return Vec3(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar));
}

double angle_between(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

uint32_t pow2_at_least(double v, uint32_t lo, uint32_t hi) {
  uint32_t p = lo;
  while (p < hi && p < v) p *= 2;
  return p;
}

}  // namespace

// Lookup cells over [lo, lo + cells / scale) for ascending borders: each cell counts the borders before it and
// keeps the one inside it. A key's cell is computed in floating point, so "inside" reaches a margin past the
// cell's ends; a border within the margin of two cells is inside both, and such cells are searched.
std::vector<EgiBins::Cell> EgiBins::lookup_cells(const double* border, uint32_t n, double lo, uint32_t cells,
                                                 double scale) {
  const double margin = 1e-9;
  std::vector<Cell> out(cells);
  uint32_t k = 0;
  for (uint32_t c = 0; c < cells; ++c) {
    const double start = lo + c / scale - margin, end = lo + (c + 1) / scale + margin;
    while (k < n && border[k] < start) ++k;
    uint32_t inside = 0;
    while (k + inside < n && border[k + inside] <= end) ++inside;
    out[c].below = k;
    out[c].border = inside == 1 ? border[k] : std::numeric_limits<double>::infinity();
    out[c].more = inside > 1 ? inside : 0;
  }
  return out;
}

EgiBins::EgiBins(int rings) : rings_(rings), ring_step_(M_PI / std::max(rings, 1)) {
  if (rings < 1 || rings > 1000) throw Error("parameter egi rings", "must be in 1..1000, got " + std::to_string(rings));
  ring_first_.push_back(0);
  for (int r = 0; r < rings; ++r) {
    const double mid = (r + 0.5) * ring_step_;
    // As many sectors as make them about as wide (along the ring) as the ring is tall.
    const int sectors = std::max(1, int(std::lround(2.0 * M_PI * std::sin(mid) / ring_step_)));
    const double lo = r * ring_step_, hi = (r + 1) * ring_step_, width = 2.0 * M_PI / sectors;
    for (int s = 0; s < sectors; ++s) {
      const double a0 = -M_PI + s * width, a1 = a0 + width;
      const Vec3 c = direction(mid, 0.5 * (a0 + a1));
      // The farthest direction of the bin lies on its border; sampling the border finely and adding the gap
      // between samples bounds the radius from above (it only has to be conservative).
      double radius = 0.0;
      const int samples = 16;
      for (int k = 0; k <= samples; ++k) {
        const double t = double(k) / samples;
        radius = std::max({radius, angle_between(c, direction(lo, a0 + t * width)),
                           angle_between(c, direction(hi, a0 + t * width)),
                           angle_between(c, direction(lo + t * (hi - lo), a0)),
                           angle_between(c, direction(lo + t * (hi - lo), a1))});
      }
      centres_.push_back(c);
      radii_.push_back(radius + std::max(width, ring_step_) / samples);
    }
    ring_first_.push_back(uint32_t(centres_.size()));
    // Sector s starts at azimuth -pi + s * width, i.e. at angle s * width of the reversed direction (-x, -y).
    for (int s = 0; s < sectors; ++s)
      sector_start_.push_back(s == 0 ? 0.0 : pseudo_angle(std::cos(s * width), std::sin(s * width)));
  }

  // Ring cells over u = -z, whose borders -cos(r step) ascend; cells about half the narrowest ring (at the poles).
  for (int r = 1; r < rings; ++r) ring_border_u_.push_back(-std::cos(r * ring_step_));
  const uint32_t ring_cells = pow2_at_least(4.0 / (1.0 - std::cos(ring_step_)), 64, 4096);
  ring_cell_scale_ = ring_cells / 2.0;
  ring_cells_ =
      lookup_cells(ring_border_u_.data(), uint32_t(ring_border_u_.size()), -1.0, ring_cells, ring_cell_scale_);
  // Sector cells: a sector spans at least pi / sectors of pseudo-angle, so 2 x sectors cells of 4 / cells hold
  // at most one start each.
  sector_cell_first_.push_back(0);
  for (int r = 0; r < rings; ++r) {
    const uint32_t first = ring_first_[r], sectors = ring_first_[r + 1] - first;
    const uint32_t cells = pow2_at_least(2.0 * sectors, 8, 256);
    const std::vector<Cell> ring = lookup_cells(sector_start_.data() + first + 1, sectors - 1, 0.0, cells, cells / 4.0);
    sector_cells_.insert(sector_cells_.end(), ring.begin(), ring.end());
    sector_cell_first_.push_back(uint32_t(sector_cells_.size()));
  }
}

// Out of line: ring_of and sector_of stay small enough to inline.
uint32_t EgiBins::search_cell(const Cell& cell, const double* border, double key, bool strict) {
  uint32_t count = cell.below;
  for (uint32_t k = cell.below; k < cell.below + cell.more; ++k) count += strict ? border[k] < key : border[k] <= key;
  return count;
}

const EgiBins& default_egi_bins() {
  static const EgiBins bins;
  return bins;
}

double EgiBins::solid_angle(uint32_t bin) const {
  const int ring = int(std::upper_bound(ring_first_.begin(), ring_first_.end(), bin) - ring_first_.begin()) - 1;
  const double band = 2.0 * M_PI * (std::cos(ring * ring_step_) - std::cos((ring + 1) * ring_step_));
  return band / (ring_first_[ring + 1] - ring_first_[ring]);
}

namespace {

// A run of one patch's facets (in facet_order) whose histogram one thread sums.
struct EgiChunk {
  uint32_t patch, begin, end;
};

// Chunks of at most 8192 facets, so that one large patch keeps both cores busy.
std::vector<EgiChunk> egi_chunks(const SurfacePatches& patches) {
  constexpr uint32_t kChunk = 8192;
  std::vector<EgiChunk> chunks;
  for (const Patch& p : patches.patches())
    for (uint32_t b = p.first_facet; b < p.first_facet + p.facet_count; b += kChunk)
      chunks.push_back({p.id, b, std::min(b + kChunk, p.first_facet + p.facet_count)});
  return chunks;
}

}  // namespace

EgiSet::EgiSet(const SurfacePatches& patches, const EgiBins& bins) : patches_(&patches), bins_(bins) {
  const Mesh& mesh = patches.mesh();
  const uint32_t* order = patches.facet_order().data();
  const std::vector<EgiChunk> chunks = egi_chunks(patches);
  // Each chunk's histogram as its touched bins and their areas, summed in a dense array of the thread's. Chunks
  // go one at a time to whichever core is free, from 20,000 facets on; smaller meshes stay on the calling thread.
  std::vector<PatchEgi> partial(chunks.size());
  struct Scratch {
    std::vector<double> dense;
    std::vector<uint32_t> touched;
  };
  auto histogram = [&](const EgiChunk& chunk, Scratch& scratch, PatchEgi& out) {
    std::vector<double>& dense = scratch.dense;
    std::vector<uint32_t>& touched = scratch.touched;
    touched.clear();
    for (uint32_t i = chunk.begin; i < chunk.end; ++i) {
      const double a = mesh.areas[order[i]];
      if (!(a > 0.0)) continue;
      const uint32_t b = bins_.bin_of(mesh.normals[order[i]]);
      if (dense[b] == 0.0) touched.push_back(b);
      dense[b] += a;
    }
    out.bins.assign(touched.begin(), touched.end());
    out.areas.resize(touched.size());
    for (size_t k = 0; k < touched.size(); ++k) {
      out.areas[k] = dense[touched[k]];
      dense[touched[k]] = 0.0;
    }
  };
  auto fresh = [&] { return Scratch{std::vector<double>(bins_.size(), 0.0), {}}; };
  if (mesh.face_count() > 20000) {
    PerThread<Scratch> scratch(fresh);
    for_each_chunk(chunks.size(), [&](size_t c) { histogram(chunks[c], scratch.local(), partial[c]); });
  } else {
    Scratch scratch = fresh();
    for (size_t c = 0; c < chunks.size(); ++c) histogram(chunks[c], scratch, partial[c]);
  }
  // A patch's chunks are consecutive: merge their histograms, bins ascending.
  std::vector<double> dense(bins_.size(), 0.0);
  std::vector<uint32_t> touched;
  egis_.resize(patches.count());
  for (size_t c = 0; c < chunks.size();) {
    PatchEgi& egi = egis_[chunks[c].patch];
    touched.clear();
    for (const uint32_t patch = chunks[c].patch; c < chunks.size() && chunks[c].patch == patch; ++c)
      for (size_t k = 0; k < partial[c].bins.size(); ++k) {
        const uint32_t b = partial[c].bins[k];
        if (dense[b] == 0.0) touched.push_back(b);
        dense[b] += partial[c].areas[k];
      }
    std::sort(touched.begin(), touched.end());
    egi.bins.assign(touched.begin(), touched.end());
    egi.areas.resize(touched.size());
    for (size_t k = 0; k < touched.size(); ++k) {
      egi.areas[k] = dense[touched[k]];
      dense[touched[k]] = 0.0;
    }
  }
}

}  // namespace rosmill::core::segment
