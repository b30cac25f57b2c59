// Near-equal-area direction bins and the per-patch Extended Gaussian Images.
#include "rosmill/segment/egi.hpp"

#include <algorithm>
#include <Eigen/Geometry>
#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::segment {
namespace {

Vec3 direction(double polar, double azimuth) {
  return Vec3(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar));
}

double angle_between(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// A number in [0, 4) that grows with the angle of (x, y) from +X counter-clockwise, as atan2 does, but with one
// division: the "diamond angle". A zero vector (either sign) gives 0.
double pseudo_angle(double x, double y) {
  if (x == 0.0 && y == 0.0) return 0.0;
  if (y >= 0.0) return x >= 0.0 ? y / (x + y) : 1.0 - x / (y - x);
  return x < 0.0 ? 2.0 - y / (-x - y) : 3.0 + x / (x - y);
}

}  // namespace

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
  for (int r = 1; r < rings; ++r) ring_border_cos_.push_back(std::cos(r * ring_step_));
}

uint32_t EgiBins::ring_of(double z) const {
  // The ring's polar angle passes r * step where z drops below cos(r * step).
  uint32_t lo = 0, hi = uint32_t(ring_border_cos_.size());
  while (lo < hi) {
    const uint32_t mid = (lo + hi) / 2;
    if (z < ring_border_cos_[mid]) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

uint32_t EgiBins::sector_of(uint32_t ring, double x, double y) const {
  const double a = pseudo_angle(-x, -y);
  const double* first = sector_start_.data() + ring_first_[ring];
  const double* last = sector_start_.data() + ring_first_[ring + 1];
  return uint32_t(std::upper_bound(first + 1, last, a) - first) - 1;
}

uint32_t EgiBins::bin_of(const Vec3& n) const {
  const uint32_t ring = ring_of(n.z());
  return ring_first_[ring] + sector_of(ring, n.x(), n.y());
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

EgiSet::EgiSet(const SurfacePatches& patches, const EgiBins& bins) : patches_(&patches), bins_(bins) {
  const Mesh& mesh = patches.mesh();
  const int64_t n = int64_t(mesh.face_count());
  std::vector<uint32_t> bin(n);
#pragma omp parallel for schedule(static) if (n > 20000)
  for (int64_t f = 0; f < n; ++f) bin[f] = bins_.bin_of(mesh.normals[f]);

  // Each patch's facets are contiguous in facet_order: sum into a dense histogram, then keep the bins touched.
  std::vector<double> dense(bins_.size(), 0.0);
  std::vector<uint32_t> touched;
  egis_.resize(patches.count());
  for (const Patch& p : patches.patches()) {
    touched.clear();
    for (const uint32_t* f = patches.facets_begin(p); f != patches.facets_end(p); ++f) {
      const double a = mesh.areas[*f];
      if (!(a > 0.0)) continue;
      if (dense[bin[*f]] == 0.0) touched.push_back(bin[*f]);
      dense[bin[*f]] += a;
    }
    std::sort(touched.begin(), touched.end());
    PatchEgi& egi = egis_[p.id];
    egi.bins = touched;
    egi.areas.reserve(touched.size());
    for (uint32_t b : touched) {
      egi.areas.push_back(dense[b]);
      dense[b] = 0.0;
    }
  }
}

}  // namespace rosmill::segment
