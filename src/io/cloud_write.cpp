#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "rosmill/error.hpp"
#include "rosmill/io/cloud_io.hpp"

namespace rosmill::core {

void write_cloud(const std::string& path, const PointCloud& cloud, Units units) {
  if (cloud.points.empty()) throw Error(path, "no point to write");
  const double scale = 1.0 / mm_per_unit(units);
  pcl::PointCloud<pcl::PointXYZ> out;
  out.reserve(cloud.points.size());
  for (const Vec3& p : cloud.points) {
    const Vec3 q = p * scale;
    out.push_back(pcl::PointXYZ(float(q.x()), float(q.y()), float(q.z())));
  }
  if (pcl::io::savePCDFileBinary(path, out) != 0) throw Error(path, "could not write the point cloud");
}

}  // namespace rosmill::core
