#include "rosmill/scan/surface_normals.hpp"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/scan/point_index.hpp"

namespace rosmill::core::scan {

std::vector<Vec3> estimate_normals(const std::vector<Vec3>& points, int neighbours, std::vector<double>* variation) {
  if (neighbours < 3 || points.size() < size_t(neighbours))
    throw Error("normal estimation", "needs at least " + std::to_string(std::max(neighbours, 3)) + " points");
  const PointIndex index(points);
  std::vector<Vec3> out(points.size());
  if (variation) variation->assign(points.size(), 0.0);
  for_each_piece<size_t>(0, points.size(), 256, [&](size_t begin, size_t end) {
    std::vector<size_t> near(static_cast<size_t>(neighbours));
    std::vector<double> sq(static_cast<size_t>(neighbours));
    for (size_t i = begin; i != end; ++i) {
      const size_t found = index.nearest_k(points[i], near.size(), near.data(), sq.data());
      // The covariance about the neighbours' centroid, taken relative to the point itself so that a millimetre
      // cloud far from its origin keeps its precision.
      Vec3 mean = Vec3::Zero();
      for (size_t k = 0; k < found; ++k) mean += points[near[k]] - points[i];
      mean /= double(found);
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (size_t k = 0; k < found; ++k) {
        const Vec3 d = points[near[k]] - points[i] - mean;
        cov += d * d.transpose();
      }
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
      const Vec3 normal = es.eigenvectors().col(0);  // the direction of least spread
      const bool plane = found >= 3 && es.eigenvalues()[2] > 0 && normal.allFinite();
      out[i] = plane ? Vec3(normal.normalized()) : Vec3::UnitZ();
      if (variation) (*variation)[i] = plane ? std::max(0.0, es.eigenvalues()[0]) / es.eigenvalues().sum() : 1.0 / 3;
    }
  });
  return out;
}

}  // namespace rosmill::core::scan
