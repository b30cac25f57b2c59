// The Extended Gaussian Image (Horn 1984; Lefebvre & Lauwers, section 3.3) of each surface patch: the facets' area
// summed per
// direction bin on the unit sphere. The bins are rings of equal polar angle cut into sectors whose count follows
// the ring's circumference, so every bin has nearly the same area and a nearly square shape (unlike a plain
// latitude-longitude grid, whose bins shrink to slivers at the poles).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rosmill/segment/surface_patches.hpp"

namespace rosmill::core::segment {

class EgiBins {
 public:
  // `rings` rings of 180/rings degrees from +Z (ring 0) to -Z; 18 rings give 412 bins of about 10 x 10 degrees.
  explicit EgiBins(int rings = 18);

  size_t size() const { return centres_.size(); }
  int rings() const { return rings_; }
  // Bin of a unit direction (callers leave out facets without area: a zero vector has no meaningful bin).
  // Inline: the EGI calls it for every facet.
  uint32_t bin_of(const Vec3& n) const {
    const uint32_t ring = ring_of(n.z());
    return ring_first_[ring] + sector_of(ring, n.x(), n.y());
  }
  // Unit direction at the middle of a bin, and the largest angle (radians) from it to any direction in the bin.
  const Vec3& centre(uint32_t bin) const { return centres_[bin]; }
  double radius(uint32_t bin) const { return radii_[bin]; }
  // Solid angle of a bin (steradians); they sum to 4 pi.
  double solid_angle(uint32_t bin) const;

 private:
  // bin_of without acos, atan2 or a search (they were most of the EGI's cost, and a binary search's branches
  // mispredict on a curved part's normals): the ring and the sector are each found in a lookup cell holding the
  // count of borders below it and the one border inside it, compared without a branch. A cell holding several
  // borders (very fine bins near the poles) searches its few.
  struct Cell {
    double border;   // the one border inside the cell (+infinity when the cell holds none)
    uint32_t below;  // borders before the cell
    uint32_t more;   // borders inside the cell when more than one (then searched), else 0
  };
  // Cells over [lo, lo + cells / scale) for ascending borders.
  static std::vector<Cell> lookup_cells(const double* border, uint32_t n, double lo, uint32_t cells, double scale);
  // The count in a cell holding several borders (rare: fine bins near the poles): borders [below, below + more)
  // strictly below the key (`strict`), or at or below it.
  [[gnu::noinline]] static uint32_t search_cell(const Cell& cell, const double* border, double key, bool strict);

  // A number in [0, 4] that grows with the angle of (x, y) from +X counter-clockwise, as atan2 does, but with one
  // division and no branch: the "diamond angle" (quadrant base plus or minus |y| / (|x| + |y|)). A zero vector
  // (either sign) gives 0.
  static double pseudo_angle(double x, double y) {
    const double ax = std::abs(x), ay = std::abs(y), sum = ax + ay;
    const double t = ay / (sum + double(sum == 0.0));
    const int right = x >= 0.0, up = y >= 0.0;
    // Quadrant bases 0 (+x +y), 2 (-x), 4 (+x -y); t counts forward where x and y agree in sign, back otherwise.
    return double(2 + right * (2 - 4 * up)) + double(1 - 2 * (right ^ up)) * t;
  }

  uint32_t ring_of(double z) const {
    // A ring is the number of borders strictly below u = -z (strictly above z).
    const double u = -z;
    const int c = std::clamp(int((u + 1.0) * ring_cell_scale_), 0, int(ring_cells_.size()) - 1);
    const Cell& cell = ring_cells_[c];
    if (cell.more) return search_cell(cell, ring_border_u_.data(), u, true);
    return cell.below + (cell.border < u);
  }

  uint32_t sector_of(uint32_t ring, double x, double y) const {
    // A sector is the number of starts after the first at or below the pseudo-angle.
    const double a = pseudo_angle(-x, -y);
    const uint32_t first = sector_cell_first_[ring], cells = sector_cell_first_[ring + 1] - first;
    const int c = std::clamp(int(a * (cells / 4.0)), 0, int(cells) - 1);
    const Cell& cell = sector_cells_[first + c];
    if (cell.more) return search_cell(cell, sector_start_.data() + ring_first_[ring] + 1, a, false);
    return cell.below + (cell.border <= a);
  }


  int rings_;
  double ring_step_;
  std::vector<uint32_t> ring_first_;  // first bin of each ring, plus the total at the end
  // The ring borders as u = -cos(r step), r = 1..rings-1 (ascending): a ring is the number strictly below -z.
  std::vector<double> ring_border_u_;
  // Per ring the pseudo-angles of its sectors' starts (one per bin, the first 0): a sector is the number of
  // starts after the first at or below the pseudo-angle.
  std::vector<double> sector_start_;
  std::vector<Cell> ring_cells_;      // over -z in [-1, 1]
  double ring_cell_scale_ = 0.0;      // cells per unit of -z
  std::vector<Cell> sector_cells_;    // each ring's cells over the pseudo-angle in [0, 4)
  std::vector<uint32_t> sector_cell_first_;  // first cell of each ring, plus the total at the end
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

}  // namespace rosmill::core::segment
