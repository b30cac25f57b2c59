#include "rosmill/cloud/cloud_input.hpp"

#include "rosmill/error.hpp"

namespace rosmill::core {

CloudPrepOptions cloud_prep_options(const CloudInputOptions& o, const std::string& prefix) {
  CloudPrepOptions prep;
  prep.units = Units::Millimetre;
  if (o.orient == "ransac") prep.orientation = Orientation::Ransac;
  else if (o.orient == "lowest") prep.orientation = Orientation::LowestFit;
  else if (o.orient != "none") throw Error(prefix + "orient", "'" + o.orient + "' is not none, ransac or lowest");
  if (o.origin != "corner" && o.origin != "keep")
    throw Error(prefix + "origin", "'" + o.origin + "' is not corner or keep");
  prep.origin_at_corner = o.origin == "corner";
  if (!(o.voxel >= 0)) throw Error(prefix + "voxel", "must be >= 0 mm");
  if (o.outliers < 0) throw Error(prefix + "outliers", "must be >= 0 neighbours");
  prep.voxel = o.voxel;
  prep.outlier_neighbours = o.outliers;
  return prep;
}

HolePolicy cloud_hole_policy(const CloudInputOptions& o, const std::string& prefix) {
  return parse_hole_policy(o.holes, prefix + "holes");
}

PointCloud prepare_input_cloud(const std::vector<Vec3>& points, const CloudInputOptions& o, const std::string& prefix,
                               CloudPrepReport* report) {
  return prepare_cloud(points, cloud_prep_options(o, prefix), report);
}

}  // namespace rosmill::core
