// The Extended Gaussian Image (Horn 1984; seed 001, 3.3) of each surface patch: the facets' area summed per
// direction bin on the unit sphere. The bins are rings of equal polar angle cut into sectors whose count follows
// the ring's circumference, so every bin has nearly the same area and a nearly square shape (unlike a plain
// latitude-longitude grid, whose bins shrink to slivers at the poles).
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/segment/surface_patches.hpp"

namespace rosmill::segment {

class EgiBins {
 public:
  // `rings` rings of 180/rings degrees from +Z (ring 0) to -Z; 18 rings give 412 bins of about 10 x 10 degrees.
  explicit EgiBins(int rings = 18);

  size_t size() const { return centres_.size(); }
  int rings() const { return rings_; }
  // Bin of a unit direction (callers leave out facets without area: a zero vector has no meaningful bin).
  uint32_t bin_of(const Vec3& n) const;
  // Unit direction at the middle of a bin, and the largest angle (radians) from it to any direction in the bin.
  const Vec3& centre(uint32_t bin) const { return centres_[bin]; }
  double radius(uint32_t bin) const { return radii_[bin]; }
  // Solid angle of a bin (steradians); they sum to 4 pi.
  double solid_angle(uint32_t bin) const;

 private:
  uint32_t ring_of(double z) const;
  uint32_t sector_of(uint32_t ring, double x, double y) const;

  int rings_;
  double ring_step_;
  std::vector<uint32_t> ring_first_;  // first bin of each ring, plus the total at the end
  // bin_of without acos and atan2 (they were most of the EGI's cost): the cosines of the ring borders (rings-1,
  // descending), and per ring the pseudo-angles of its sectors' starts (one per bin, the first 0).
  std::vector<double> ring_border_cos_;
  std::vector<double> sector_start_;
  std::vector<Vec3> centres_;
  std::vector<double> radii_;
};

// The default bins (18 rings), made once.
const EgiBins& default_egi_bins();

// One patch's EGI: the occupied bins (ascending) and the facet area in each.
struct PatchEgi {
  std::vector<uint32_t> bins;
  std::vector<double> areas;
};

// The EGIs of every patch of a phase 1 segmentation. Built once per mesh; every setup filter reads it.
class EgiSet {
 public:
  EgiSet(const SurfacePatches& patches, const EgiBins& bins = default_egi_bins());
  const SurfacePatches& patches() const { return *patches_; }
  const EgiBins& bins() const { return bins_; }
  const PatchEgi& egi(size_t patch) const { return egis_[patch]; }

 private:
  const SurfacePatches* patches_;
  EgiBins bins_;
  std::vector<PatchEgi> egis_;
};

}  // namespace rosmill::segment
