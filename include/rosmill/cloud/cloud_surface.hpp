// The point-cloud Surface (Muslimin et al., "Direct NC Toolpath Generation from 3D Point Cloud Datasets"):
// drop-cutter straight against scanned points, no surface reconstruction.
//
// For a cutter of radius R and corner radius r (flat r = 0, ball r = R, bull in between; Rf = R - r), a point p
// at plan distance d from the cutter axis holds the tip up at
//     d <= Rf:            z_p
//     Rf < d <= R:        z_p - r + sqrt(r² - (d - Rf)²)      (the torus; the ball's z_p + sqrt(R² - d²) - R)
// and the highest over the points under the footprint wins: Muslimin et al.'s z_c less R, the tip height.
//
// Missing data, the stated policy (never plunge into it):
//  - Holes (enclosed empty cells of a coarse plan-view grid) are covered by lids at the highest neighbouring
//    point (cloud_holes.hpp), so no strategy plunges into them.
//  - Sparse regions: between points a cutter sinks by up to g²/2r on level ground (g: the radius of the empty
//    circle it sits over, r: its corner radius), and a flat end mill's sharp edge reaches past the last point. So
//    every point stands for a level disc of radius c = max(0, ρ - sqrt(2 r s)) (ρ: the cloud's sampling radius,
//    s: the sink allowed): in the formula above, Rf and R both grow by c. Where the cloud is dense for the
//    cutter c = 0 and Muslimin et al.'s bare formula holds; where it is sparse the discs bridge the gaps and the cutter
//    stays at the neighbouring points' height. The price is stock left on slopes (at most c tan θ).
#pragma once
#include <cmath>
#include <vector>

#include "rosmill/cloud/cloud_grid.hpp"
#include "rosmill/cloud/cloud_holes.hpp"
#include "rosmill/cutter/contact.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/plan/surface.hpp"

namespace rosmill::core {

struct CloudSurfaceOptions {
  double cell = 0.0;       // index cell (mm); 0: about four points per cell
  double hole_cell = 0.0;  // hole-detection cell (mm); 0: auto_hole_cell()
  bool detect_holes = true;
  double sampling_radius = NAN;  // ρ (mm); NaN: estimated (rosmill::core::sampling_radius); 0: the bare formula always
  double max_sink = 0.01;        // s (mm): how far a cutter may sink between points on level ground
  HolePolicy holes = HolePolicy::Bridge;  // Skip: skips() is true where a footprint reaches a hole
};

class CloudSurface : public Surface {
 public:
  explicit CloudSurface(const PointCloud& cloud, const CloudSurfaceOptions& options = {});
  explicit CloudSurface(const std::vector<Vec3>& points, const CloudSurfaceOptions& options = {});

  Box3 bounds() const override { return grid_.bounds(); }
  // Untouched (nothing under the footprint, no lid): z is the cloud's lowest point, the stock's floor.
  Drop drop(const Cutter& cutter, double x, double y) const override;
  // Both cores (TBB); each query allocates nothing.
  void drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const override;
  // Exact against the points themselves (cloud_sweep.hpp).
  SweepHit sweep(const Cutter& cutter, const Vec3& a, const Vec3& b, double floor) const override;
  // HolePolicy::Skip: the footprint reaches a hole. Bridge: never (the lids carry the cutter).
  bool skips(double x, double y, double radius) const override;

  size_t size() const { return grid_.size(); }
  double mean_spacing() const { return spacing_; }
  double sampling_radius() const { return sampling_radius_; }
  // c for this cutter: the radius of the level disc every point stands for (see above).
  double support_radius(const Cutter& cutter) const;
  // The cutter as the points see it: its flat part grown by support_radius() (a bull nose; itself when c = 0).
  Cutter supported(const Cutter& cutter) const;
  const CloudGrid& grid() const { return grid_; }
  const HoleMap& holes() const { return holes_; }

 private:
  void build(const std::vector<Vec3>& points, const CloudSurfaceOptions& options);
  // The drop with the profiles prepared (points: supported(cutter); lids: the cutter itself) and `hint`, the
  // point that held the cutter at a nearby position (or null), updated to this position's.
  Drop drop_hinted(const CutterProfile& cp, const CutterProfile& lid_cp, double x, double y,
                   const GridPoint*& hint) const;

  CloudGrid grid_;
  HoleMap holes_;
  double spacing_ = 0.0;
  double sampling_radius_ = 0.0;
  double max_sink_ = 0.01;
  HolePolicy hole_policy_ = HolePolicy::Bridge;
};

}  // namespace rosmill::core
