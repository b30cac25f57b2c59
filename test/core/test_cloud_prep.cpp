// Cloud preparation (cloud_prep.hpp, the seed's step 1) and the step-error interpolation (plan/step_error.hpp):
// orientation by a given transform and by fitting the base plane, origin at the stock corner, units, NaN/inf
// dropped, voxel downsampling and outlier removal counted, holes reported; step errors and buffer points.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "rosmill/plan/step_error.hpp"
#include "rosmill/cloud/cloud_prep.hpp"
#include "rosmill/error.hpp"

using namespace rosmill::core;

namespace {

// A 60 x 40 mm table (z = 0, 0.5 mm pitch) with a 20 x 20 x 10 mm block on it and a 6 x 6 mm hole in the table.
std::vector<Vec3> table_and_block() {
  std::vector<Vec3> pts;
  for (double x = 0; x <= 60 + 1e-9; x += 0.5)
    for (double y = 0; y <= 40 + 1e-9; y += 0.5) {
      const bool block = x >= 20 && x <= 40 && y >= 10 && y <= 30;
      const bool hole = x > 6 && x < 12 && y > 6 && y < 12;
      if (hole) continue;
      pts.push_back(Vec3(x, y, block ? 10.0 : 0.0));
    }
  return pts;
}

// A rigid motion: rotation by `deg` about a tilted axis, then a shift.
Eigen::Matrix4d motion(double deg) {
  Eigen::Affine3d a = Eigen::Translation3d(120, -40, 300) *
                      Eigen::AngleAxisd(deg * M_PI / 180, Vec3(1, 2, 0.5).normalized());
  return a.matrix();
}

std::vector<Vec3> moved(const std::vector<Vec3>& pts, const Eigen::Matrix4d& m) {
  std::vector<Vec3> out;
  for (const Vec3& p : pts) out.push_back((m * p.homogeneous()).head<3>());
  return out;
}

}  // namespace

TEST(CloudPrep, RansacFindsTheBaseTableFacingUpWithTheOriginAtTheCorner) {
  const std::vector<Vec3> truth = table_and_block();
  const std::vector<Vec3> scan = moved(truth, motion(35));
  CloudPrepOptions o;
  o.orientation = Orientation::Ransac;
  CloudPrepReport r;
  const PointCloud c = prepare_cloud(scan, o, &r);
  ASSERT_EQ(c.points.size(), truth.size());
  // PCL fits in float: positions within a micrometre. The table at z = 0, the block's top at z = 10 (normal +Z, most
  // points above the plane).
  size_t table = 0, top = 0;
  for (const Vec3& p : c.points) {
    ASSERT_TRUE(std::abs(p.z()) < 1e-3 || std::abs(p.z() - 10) < 1e-3) << p.transpose();
    table += std::abs(p.z()) < 1e-3;
    top += std::abs(p.z() - 10) < 1e-3;
  }
  EXPECT_GT(table, top);
  EXPECT_GE(r.plane_inliers, table);
  // Origin at the stock corner: the plan-view box starts at (0, 0); the footprint keeps its 60 x 40 (in some
  // rotation about z: the diagonal and the area of the box are at least the table's).
  EXPECT_NEAR(c.bbox.min.x(), 0.0, 1e-3);
  EXPECT_NEAR(c.bbox.min.y(), 0.0, 1e-3);
  EXPECT_NEAR(c.bbox.min.z(), 0.0, 1e-3);
  EXPECT_NEAR(c.bbox.max.z(), 10.0, 1e-3);
  EXPECT_GE(c.bbox.size().head<2>().norm(), std::hypot(60.0, 40.0) - 1e-3);
  // The report: the hole in the table, density.
  EXPECT_NEAR(r.mean_spacing, 0.5, 0.01);
  ASSERT_EQ(r.holes.size(), 1u);
  EXPECT_GT(r.holes[0].area, 10.0);
  EXPECT_LT(r.holes[0].area, 60.0);
  EXPECT_NE(format_prep_report(r).find("holes: 1"), std::string::npos) << format_prep_report(r);
}

TEST(CloudPrep, GivenTransformUnitsAndNonFinitePoints) {
  std::vector<Vec3> pts = table_and_block();
  for (Vec3& p : pts) p /= 1000.0;  // metres
  pts.push_back(Vec3(NAN, 0, 0));
  pts.push_back(Vec3(0, INFINITY, 0));
  CloudPrepOptions o;
  o.units = Units::Metre;
  o.orientation = Orientation::Transform;
  o.transform = Eigen::Matrix4d::Identity();
  o.transform(2, 3) = 5.0;  // mm, after scaling
  o.origin_at_corner = false;
  CloudPrepReport r;
  const PointCloud c = prepare_cloud(pts, o, &r);
  EXPECT_EQ(r.dropped_nonfinite, 2u);
  EXPECT_EQ(c.points.size(), pts.size() - 2);
  EXPECT_NEAR(c.bbox.max.x(), 60.0, 1e-9);
  EXPECT_NEAR(c.bbox.min.z(), 5.0, 1e-9);
  EXPECT_NEAR(c.bbox.max.z(), 15.0, 1e-9);
  // Not a rigid transform: refused.
  o.transform(0, 0) = 2.0;
  EXPECT_THROW(prepare_cloud(pts, o), Error);
  // Nothing finite: refused.
  EXPECT_THROW(prepare_cloud(std::vector<Vec3>{Vec3(NAN, NAN, NAN)}, CloudPrepOptions{}), Error);
}

TEST(CloudPrep, VoxelAndOutlierFiltersAreCounted) {
  std::vector<Vec3> pts = table_and_block();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 60);
  for (int k = 0; k < 20; ++k) pts.push_back(Vec3(u(rng), u(rng) * 40 / 60, 40 + u(rng)));  // stray points above
  CloudPrepOptions o;
  o.outlier_neighbours = 8;
  CloudPrepReport r;
  PointCloud c = prepare_cloud(pts, o, &r);
  EXPECT_GE(r.removed_outliers, 20u);
  EXPECT_LT(r.removed_outliers, 200u);
  EXPECT_LE(c.bbox.max.z(), 10.0 + 1e-9) << "the stray points are gone";
  o = {};
  o.voxel = 2.0;
  c = prepare_cloud(table_and_block(), o, &r);
  EXPECT_EQ(r.after_voxel, c.points.size());
  EXPECT_LT(c.points.size(), table_and_block().size() / 10);
  EXPECT_GT(c.points.size(), 60u * 40u / 4u / 2u);  // about one per 2 x 2 mm of table
  o.voxel = -1;
  EXPECT_THROW(prepare_cloud(table_and_block(), o), Error);
}

TEST(CloudInterpolation, StepErrorAndBufferPointsBoundEverySample) {
  EXPECT_NEAR(step_error(Vec3(0, 0, 0), Vec3(10, 0, 10), Vec3(5, 0, 7)), 2.0, 1e-12);
  EXPECT_NEAR(step_error(Vec3(0, 0, 0), Vec3(0, 10, 0), Vec3(0, 5, -1)), -1.0, 1e-12);
  // A ball's CL over a bump, sampled finely: the kept points bring every sample within eps of its chord.
  std::vector<Vec3> cl;
  std::vector<uint8_t> corner;
  for (int i = 0; i <= 400; ++i) {
    const double x = i * 0.1;
    cl.push_back(Vec3(x, 0, 5 * std::exp(-(x - 20) * (x - 20) / 20)));
    corner.push_back(0);
  }
  std::vector<uint32_t> kept;
  const double eps = 0.005;
  const size_t buffers = buffer_points(cl, corner, 0, cl.size() - 1, 6.0, eps, kept);
  ASSERT_GE(kept.size(), 2u);
  EXPECT_EQ(kept.front(), 0u);
  EXPECT_EQ(kept.back(), cl.size() - 1);
  EXPECT_GT(buffers, 10u);
  EXPECT_LT(kept.size(), cl.size() / 2);
  for (size_t k = 1; k < kept.size(); ++k) {
    ASSERT_LT(kept[k - 1], kept[k]);
    EXPECT_LE(cl[kept[k]].x() - cl[kept[k - 1]].x(), 6.0 + 1e-9);  // at most the interval apart
    for (uint32_t i = kept[k - 1] + 1; i < kept[k]; ++i)
      ASSERT_LE(std::abs(step_error(cl[kept[k - 1]], cl[kept[k]], cl[i])), eps + 1e-12) << i;
  }
}
