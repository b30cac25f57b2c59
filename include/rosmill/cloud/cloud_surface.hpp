// The point-cloud Surface (seed 004): drop-cutter straight against scanned points, no surface reconstruction.
//
// For a cutter of radius R and corner radius r (flat r = 0, ball r = R, bull in between; Rf = R - r), a point p
// at plan distance d from the cutter axis holds the tip up at
//     d <= Rf:            z_p
//     Rf < d <= R:        z_p - r + sqrt(r² - (d - Rf)²)      (the torus; the ball's z_p + sqrt(R² - d²) - R)
// and the highest over the points under the footprint wins: the seed's z_c less R, the tip height.
// Enclosed holes are covered by lids (cloud_holes.hpp), so no strategy plunges into missing data.
#pragma once
#include <vector>

#include "rosmill/cloud/cloud_grid.hpp"
#include "rosmill/cloud/cloud_holes.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/plan/surface.hpp"

namespace rosmill {

struct CloudSurfaceOptions {
  double cell = 0.0;       // index cell (mm); 0: about four points per cell
  double hole_cell = 0.0;  // hole-detection cell (mm); 0: auto_hole_cell()
  bool detect_holes = true;
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

  size_t size() const { return grid_.size(); }
  double mean_spacing() const { return spacing_; }
  const CloudGrid& grid() const { return grid_; }
  const HoleMap& holes() const { return holes_; }

 private:
  void build(const std::vector<Vec3>& points, const CloudSurfaceOptions& options);

  CloudGrid grid_;
  HoleMap holes_;
  double spacing_ = 0.0;
};

}  // namespace rosmill
