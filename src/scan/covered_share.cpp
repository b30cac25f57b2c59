#include "rosmill/scan/covered_share.hpp"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

namespace rosmill::core::scan {

double covered_share(const std::vector<Vec3>& queries, const std::vector<Vec3>& cloud, double radius) {
  if (queries.empty() || cloud.empty()) return 0;
  const Vec3 origin = cloud.front();  // float coordinates near zero keep their precision
  const auto to_pcl = [&](const Vec3& p) {
    const Eigen::Vector3f q = (p - origin).cast<float>();
    return pcl::PointXYZ(q.x(), q.y(), q.z());
  };
  pcl::PointCloud<pcl::PointXYZ>::Ptr points(new pcl::PointCloud<pcl::PointXYZ>);
  points->reserve(cloud.size());
  for (const Vec3& p : cloud) points->push_back(to_pcl(p));
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(points);
  size_t covered = 0;
  pcl::Indices index(1);
  std::vector<float> sq(1);
  for (const Vec3& p : queries)
    if (tree.nearestKSearch(to_pcl(p), 1, index, sq) > 0 && sq[0] <= radius * radius) ++covered;
  return double(covered) / double(queries.size());
}

}  // namespace rosmill::core::scan
