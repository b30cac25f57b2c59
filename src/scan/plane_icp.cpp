#include "rosmill/scan/plane_icp.hpp"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>

#include "rosmill/error.hpp"

namespace rosmill::core::scan {

using Cloud = pcl::PointCloud<pcl::PointNormal>;

// PCL computes in float: both clouds go in relative to the fixed surface's centroid, so millimetre parts far
// from their origin keep micrometre precision.
struct PlaneIcp::Impl {
  Vec3 origin = Vec3::Zero();
  mutable pcl::IterativeClosestPointWithNormals<pcl::PointNormal, pcl::PointNormal> icp;
};

PlaneIcp::PlaneIcp(const std::vector<Vec3>& points, const std::vector<Vec3>& normals) : impl_(std::make_unique<Impl>()) {
  if (points.empty()) throw Error("point-to-plane ICP", "the fixed surface has no point");
  if (points.size() != normals.size()) throw Error("point-to-plane ICP", "one normal per point is needed");
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : points) sum += p;
  impl_->origin = sum / double(points.size());
  Cloud::Ptr target(new Cloud);
  target->reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    pcl::PointNormal q;
    q.getVector3fMap() = (points[i] - impl_->origin).cast<float>();
    q.getNormalVector3fMap() = normals[i].cast<float>();
    target->push_back(q);
  }
  impl_->icp.setInputTarget(target);
}

PlaneIcp::~PlaneIcp() = default;

Eigen::Matrix4d PlaneIcp::align(const std::vector<Vec3>& moving, const Eigen::Matrix4d& start, double max_distance,
                                int iterations) const {
  if (moving.size() < 6) throw Error("point-to-plane ICP", "at least 6 moving points are needed");
  Eigen::Matrix4d shift = Eigen::Matrix4d::Identity();
  shift.topRightCorner<3, 1>() = -impl_->origin;
  const Eigen::Matrix4d begin = shift * start;
  const Eigen::Matrix3d r = begin.topLeftCorner<3, 3>();
  const Vec3 t = begin.topRightCorner<3, 1>();
  Cloud::Ptr source(new Cloud);
  source->reserve(moving.size());
  for (const Vec3& p : moving) {
    pcl::PointNormal q;
    q.getVector3fMap() = (r * p + t).cast<float>();
    q.getNormalVector3fMap() = Eigen::Vector3f::UnitZ();  // unused: the fixed surface's normals are the planes
    source->push_back(q);
  }
  auto& icp = impl_->icp;
  icp.setInputSource(source);
  icp.setMaxCorrespondenceDistance(max_distance);
  icp.setMaximumIterations(iterations);
  icp.setTransformationEpsilon(1e-12);            // squared translation step: 1e-6 mm
  icp.setTransformationRotationEpsilon(1 - 5e-13);  // cosine of the rotation step: 1e-6 rad
  icp.setEuclideanFitnessEpsilon(-1);              // never stop on the fitness alone
  Cloud aligned;
  icp.align(aligned);
  const Eigen::Matrix4d step = icp.getFinalTransformation().cast<double>();
  Eigen::Matrix4d unshift = Eigen::Matrix4d::Identity();
  unshift.topRightCorner<3, 1>() = impl_->origin;
  return unshift * step * begin;
}

}  // namespace rosmill::core::scan
