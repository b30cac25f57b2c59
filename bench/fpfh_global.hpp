// The peer of registration's global step: PCL's feature-based alignment with no initial guess, as its tutorial
// "Robust pose estimation of rigid objects" runs it — FPFH features (Rusu et al., "Fast Point Feature Histograms
// (FPFH) for 3D registration", 2009) on a voxel-thinned scan and on samples of the design, matched and sampled by
// SampleConsensusPrerejective (Buch et al., "Pose estimation using local structure-specific shape and appearance
// context", 2013). Both feature steps run on every core (the OMP estimators). Only the bench uses it: the product's
// global step is principal axes with symmetry probes (src/scan/design_registration.cpp).
#pragma once
#include <chrono>
#include <vector>

#include <Eigen/Core>
#include <pcl/features/fpfh_omp.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/point_types.h>
#include <pcl/registration/sample_consensus_prerejective.h>

#include "rosmill/geometry/types.hpp"

namespace rosmill::bench {

struct FpfhGlobal {
  Eigen::Matrix4d design_to_scan = Eigen::Matrix4d::Identity();
  bool converged = false;
  double seconds = 0;
  double inlier_share = 0;  // of the thinned scan, as SampleConsensusPrerejective counts them
};

// `scan`: the scan's points (mm) and a point of view to orient its normals (the sensor's position, as a scanner's
// cloud gives it); `design_points`, `design_normals`: samples of the design with its outward normals; `leaf`: the
// voxel (mm) the scan is thinned to, the feature radius 5 leaves and the inlier distance 2.5.
inline FpfhGlobal fpfh_global(const std::vector<core::Vec3>& scan, const core::Vec3& viewpoint,
                              const std::vector<core::Vec3>& design_points,
                              const std::vector<core::Vec3>& design_normals, double leaf) {
  using Cloud = pcl::PointCloud<pcl::PointNormal>;
  using Features = pcl::PointCloud<pcl::FPFHSignature33>;
  const auto start = std::chrono::steady_clock::now();
  Cloud::Ptr source(new Cloud), target(new Cloud);
  for (const core::Vec3& p : scan) {
    pcl::PointNormal q;
    q.x = float(p.x()), q.y = float(p.y()), q.z = float(p.z());
    source->push_back(q);
  }
  pcl::NormalEstimationOMP<pcl::PointNormal, pcl::PointNormal> normals;
  normals.setInputCloud(source);
  normals.setRadiusSearch(3 * leaf);
  normals.setViewPoint(float(viewpoint.x()), float(viewpoint.y()), float(viewpoint.z()));
  normals.compute(*source);
  for (size_t i = 0; i < design_points.size(); ++i) {
    pcl::PointNormal q;
    q.x = float(design_points[i].x()), q.y = float(design_points[i].y()), q.z = float(design_points[i].z());
    q.normal_x = float(design_normals[i].x()), q.normal_y = float(design_normals[i].y());
    q.normal_z = float(design_normals[i].z());
    target->push_back(q);
  }
  const auto features = [&](const Cloud::Ptr& cloud) {
    Features::Ptr out(new Features);
    pcl::FPFHEstimationOMP<pcl::PointNormal, pcl::PointNormal, pcl::FPFHSignature33> fpfh;
    fpfh.setInputCloud(cloud);
    fpfh.setInputNormals(cloud);
    fpfh.setRadiusSearch(5 * leaf);
    fpfh.compute(*out);
    return out;
  };
  const Features::Ptr source_features = features(source), target_features = features(target);
  pcl::SampleConsensusPrerejective<pcl::PointNormal, pcl::PointNormal, pcl::FPFHSignature33> align;
  align.setInputSource(source);
  align.setSourceFeatures(source_features);
  align.setInputTarget(target);
  align.setTargetFeatures(target_features);
  align.setMaximumIterations(50000);
  align.setNumberOfSamples(3);
  align.setCorrespondenceRandomness(5);
  align.setSimilarityThreshold(0.9f);
  align.setMaxCorrespondenceDistance(2.5 * leaf);
  align.setInlierFraction(0.25f);
  Cloud aligned;
  align.align(aligned);
  FpfhGlobal r;
  r.converged = align.hasConverged();
  const Eigen::Matrix4d scan_to_design = align.getFinalTransformation().cast<double>();
  r.design_to_scan = scan_to_design.inverse();
  r.inlier_share = source->empty() ? 0 : double(align.getInliers().size()) / double(source->size());
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace rosmill::bench
