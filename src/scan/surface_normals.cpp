#include "rosmill/scan/surface_normals.hpp"

#include <pcl/features/normal_3d.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include "rosmill/error.hpp"

namespace rosmill::core::scan {

std::vector<Vec3> estimate_normals(const std::vector<Vec3>& points, int neighbours) {
  if (neighbours < 3 || points.size() < size_t(neighbours))
    throw Error("normal estimation", "needs at least " + std::to_string(std::max(neighbours, 3)) + " points");
  // Float coordinates relative to the first point keep the precision of a millimetre cloud far from its origin.
  const Vec3 origin = points.front();
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(points.size());
  for (const Vec3& p : points) {
    const Eigen::Vector3f q = (p - origin).cast<float>();
    cloud->push_back(pcl::PointXYZ(q.x(), q.y(), q.z()));
  }
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimation;
  estimation.setInputCloud(cloud);
  estimation.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
  estimation.setKSearch(neighbours);
  pcl::PointCloud<pcl::Normal> normals;
  estimation.compute(normals);
  std::vector<Vec3> out;
  out.reserve(points.size());
  for (const auto& n : normals) {
    const Vec3 v(n.normal_x, n.normal_y, n.normal_z);
    out.push_back(v.allFinite() && v.norm() > 0.5 ? Vec3(v.normalized()) : Vec3::UnitZ());
  }
  return out;
}

}  // namespace rosmill::core::scan
