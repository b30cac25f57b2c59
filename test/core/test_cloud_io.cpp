// Point cloud input on the real clouds (counts from ../shared/data/README.md) and on broken files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/io/cloud_io.hpp"

using namespace rosmill::core;

namespace {

std::string temp_path(const std::string& name) {
  return testing::TempDir() + "rosmill_test_cloud_" + std::to_string(::getpid()) + "_" + name;
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Runs read_cloud and returns the error message (empty when it did not throw).
std::string cloud_error(const std::string& path) {
  try {
    read_cloud(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

struct CloudFile {
  const char* file;
  const char* format;
  size_t points;
};

}  // namespace

TEST(CloudIo, RealCloudsLoadWithTheirPointCounts) {
  const CloudFile files[] = {
      {"pcl_bunny.pcd", "pcd", 397},
      {"pcl_milk.pcd", "pcd", 13704},
      {"snp_part_scan.ply", "ply", 3627},
      {"snp_blending_part_scan.ply", "ply", 1735},  // x, y, z stored as double
      {"noether_wavy_mesh_with_hole.ply", "ply", 757},
  };
  for (const CloudFile& f : files) {
    SCOPED_TRACE(f.file);
    CloudInfo info;
    const PointCloud cloud = read_cloud(std::string(ROSMILL_TEST_DATA "/") + f.file, {}, &info);
    EXPECT_EQ(cloud.points.size(), f.points);
    EXPECT_EQ(info.points_in_file, f.points);
    EXPECT_EQ(info.dropped_nonfinite, 0u);
    EXPECT_EQ(info.format, f.format);
    EXPECT_FALSE(cloud.bbox.empty());
    for (const Vec3& p : cloud.points) ASSERT_TRUE(p.allFinite());
  }
}

TEST(CloudIo, OrganisedCloudDropsAndCountsNaNs) {
  CloudInfo info;
  const PointCloud cloud = read_cloud(ROSMILL_TEST_DATA "/pcl_table_scene_mug_stereo_textured.pcd", {}, &info);
  EXPECT_EQ(info.points_in_file, 307200u);
  EXPECT_EQ(cloud.points.size(), 209280u);
  EXPECT_EQ(info.dropped_nonfinite, 307200u - 209280u);
}

TEST(CloudIo, UnitsScaleToMillimetres) {
  // The bunny is in metres (about 0.15 m across); read as metres it is about 150 mm.
  CloudReadOptions metres;
  const PointCloud mm = read_cloud(ROSMILL_TEST_DATA "/pcl_bunny.pcd", metres);
  CloudReadOptions as_mm;
  as_mm.units = Units::Millimetre;
  const PointCloud raw = read_cloud(ROSMILL_TEST_DATA "/pcl_bunny.pcd", as_mm);
  ASSERT_EQ(mm.points.size(), raw.points.size());
  EXPECT_NEAR(mm.points[0].x(), 1000.0 * raw.points[0].x(), 1e-9);
  EXPECT_GT(mm.bbox.size().x(), 100.0);
  EXPECT_LT(mm.bbox.size().x(), 200.0);
  EXPECT_NEAR(raw.points[0].x(), 0.0054216, 1e-7);
}

TEST(CloudIo, AllNaNCloudIsAnErrorNamingTheFile) {
  const std::string path = write_temp("nan.pcd",
                                      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                                      "WIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n"
                                      "nan nan nan\nnan 1 2\n");
  const std::string msg = cloud_error(path);
  std::remove(path.c_str());
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("NaN"), std::string::npos) << msg;
}

TEST(CloudIo, EmptyCloudIsAnError) {
  const std::string path = write_temp("zero.pcd",
                                      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                                      "WIDTH 0\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 0\nDATA ascii\n");
  const std::string msg = cloud_error(path);
  std::remove(path.c_str());
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_TRUE(msg.find("empty") != std::string::npos || msg.find("cannot read") != std::string::npos) << msg;
}

TEST(CloudIo, BadFilesGiveErrorsNamingTheFile) {
  const std::string missing = temp_path("missing.pcd");
  EXPECT_NE(cloud_error(missing).find(missing + ": no such file"), std::string::npos);
  const std::string dir = testing::TempDir();
  EXPECT_NE(cloud_error(dir).find("is a directory"), std::string::npos);
  const std::string empty = write_temp("empty.ply", "");
  EXPECT_NE(cloud_error(empty).find(empty + ": empty file"), std::string::npos);
  std::remove(empty.c_str());
  const std::string garbage = write_temp("garbage.pcd", "this is not a point cloud\n");
  const std::string msg = cloud_error(garbage);
  std::remove(garbage.c_str());
  EXPECT_NE(msg.find(garbage), std::string::npos) << msg;
  const std::string no_z = write_temp("noz.pcd",
                                      "VERSION 0.7\nFIELDS x y\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\n"
                                      "WIDTH 1\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n1 2\n");
  const std::string msg_z = cloud_error(no_z);
  std::remove(no_z.c_str());
  EXPECT_NE(msg_z.find("no 'z' field"), std::string::npos) << msg_z;
}

TEST(CloudIo, CloudPathsAreToldByExtension) {
  EXPECT_TRUE(is_cloud_path("scan.pcd"));
  EXPECT_TRUE(is_cloud_path("dir.v2/scan.PLY"));
  EXPECT_FALSE(is_cloud_path("part.stl"));
  EXPECT_FALSE(is_cloud_path("dir.pcd/part"));
}

TEST(CloudIo, TruncatedFilesAreErrorsNotCrashes) {
  // PCL trusts headers; the layout is checked first, so a cut file is an error naming it, never a crash.
  for (const char* file : {"pcl_milk.pcd", "pcl_table_scene_mug_stereo_textured.pcd", "snp_part_scan.ply",
                           "noether_wavy_mesh_with_hole.ply", "pcl_bunny.pcd"}) {
    SCOPED_TRACE(file);
    std::ifstream in(std::string(ROSMILL_TEST_DATA "/") + file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (size_t keep : {size_t(10), size_t(300), bytes.size() / 2}) {
      const std::string path = write_temp(std::string("cut_") + file + (std::string(file).find(".pcd") !=
                                                                          std::string::npos ? ".pcd" : ".ply"),
                                          bytes.substr(0, keep));
      const std::string msg = cloud_error(path);
      std::remove(path.c_str());
      EXPECT_NE(msg.find(path), std::string::npos) << "kept " << keep << " bytes: '" << msg << "'";
    }
  }
}
