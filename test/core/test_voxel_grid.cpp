// The voxel grid filter (voxel_grid.hpp): known centroids and order on a lattice, agreement with PCL's VoxelGrid on
// a real stereo scan, and clear errors for a bad leaf or point.
#include <gtest/gtest.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "rosmill/cloud/voxel_grid.hpp"
#include "rosmill/error.hpp"
#include "rosmill/io/cloud_io.hpp"

using namespace rosmill::core;

TEST(VoxelGrid, CentroidsPerCellInPclOrder) {
  // Two points in each of the cells (0,0,0), (1,0,0), (0,1,0) and (0,0,1) of a 2 mm grid anchored at (10, 20, 30);
  // given in reverse order, they come out x fastest, then y, then z.
  const Vec3 corner(10, 20, 30);
  std::vector<Vec3> pts;
  for (const Vec3& cell : {Vec3(0, 0, 1), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 0)}) {
    pts.push_back(corner + 2 * cell + Vec3(0.0, 0.5, 1.0));
    pts.push_back(corner + 2 * cell + Vec3(1.0, 1.5, 0.0));
  }
  const std::vector<Vec3> out = voxel_centroids(pts, 2.0);
  ASSERT_EQ(out.size(), 4u);
  const Vec3 mid(0.5, 1.0, 0.5);
  EXPECT_LT((out[0] - (corner + mid)).norm(), 1e-12);
  EXPECT_LT((out[1] - (corner + Vec3(2, 0, 0) + mid)).norm(), 1e-12);
  EXPECT_LT((out[2] - (corner + Vec3(0, 2, 0) + mid)).norm(), 1e-12);
  EXPECT_LT((out[3] - (corner + Vec3(0, 0, 2) + mid)).norm(), 1e-12);
  // The highest point of the cloud lies on the last cell's upper face: it stays in that cell.
  pts = {Vec3(0, 0, 0), Vec3(4, 4, 4)};
  EXPECT_EQ(voxel_centroids(pts, 2.0).size(), 2u);
  EXPECT_TRUE(voxel_centroids({}, 1.0).empty());
  // A grid of more than 2^32 cells (2001^3 here) takes 64-bit keys: the same answer.
  pts = {Vec3(1000, 1000, 1000), Vec3(0.1, 0.2, 0.3), Vec3(0.3, 0.2, 0.1), Vec3(0, 0, 0)};
  const std::vector<Vec3> wide = voxel_centroids(pts, 0.5);
  ASSERT_EQ(wide.size(), 2u);
  EXPECT_LT((wide[0] - Vec3(0.4, 0.4, 0.4) / 3).norm(), 1e-12);
  EXPECT_LT((wide[1] - Vec3(1000, 1000, 1000)).norm(), 1e-12);
}

TEST(VoxelGrid, AgreesWithPclOnARealScan) {
  // PCL's stereo scan of a table with a mug (209,280 finite points, read in millimetres) on a 4.7 mm grid, given to
  // PCL in float relative to the cloud's corner, as cloud preparation used to call it. A point within float
  // rounding of a cell face may fall on either side in float: those (about 1,200) are left out, and then every
  // cell, its centroid and its place in the order must agree.
  const std::vector<Vec3> scan = read_cloud(ROSMILL_TEST_DATA "/pcl_table_scene_mug_stereo_textured.pcd").points;
  const double leaf = double(4.7f);
  Box3 box;
  for (const Vec3& p : scan) box.add(p);
  std::vector<Vec3> pts;
  for (const Vec3& p : scan) {
    const Vec3 c = (p - box.min) / leaf;
    const Vec3 f = c.array() - c.array().floor();
    if (f.minCoeff() > 1e-5 && f.maxCoeff() < 1 - 1e-5) pts.push_back(p);
  }
  ASSERT_GT(pts.size(), 200000u);
  pts.push_back(box.min);  // the same corner for both grids
  pcl::PointCloud<pcl::PointXYZ>::Ptr in(new pcl::PointCloud<pcl::PointXYZ>);
  for (const Vec3& p : pts) {
    const Vec3 q = p - box.min;
    in->push_back(pcl::PointXYZ(float(q.x()), float(q.y()), float(q.z())));
  }
  pcl::PointCloud<pcl::PointXYZ> filtered;
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setInputCloud(in);
  grid.setLeafSize(float(leaf), float(leaf), float(leaf));
  grid.filter(filtered);

  const std::vector<Vec3> ours = voxel_centroids(pts, leaf);
  ASSERT_EQ(ours.size(), filtered.size());
  ASSERT_GT(ours.size(), 30000u);
  double worst = 0;
  for (size_t i = 0; i < ours.size(); ++i) {
    const Vec3 theirs = box.min + Vec3(filtered[i].x, filtered[i].y, filtered[i].z);
    worst = std::max(worst, (ours[i] - theirs).norm());
  }
  EXPECT_LT(worst, 2e-3) << "the same cells in the same order; centroids equal up to PCL's float sums";
}

TEST(VoxelGrid, BadLeafOrPointIsAClearError) {
  const std::vector<Vec3> pts = {Vec3(0, 0, 0), Vec3(1000, 1000, 1000)};
  for (const double leaf : {0.0, -1.0, std::nan(""), 1e-9}) {
    try {
      voxel_centroids(pts, leaf);
      ADD_FAILURE() << "leaf " << leaf << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("voxel grid"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(voxel_centroids({Vec3(0, 0, 0), Vec3(std::nan(""), 0, 0)}, 1.0), Error);
}
