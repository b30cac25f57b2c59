// STL input on the real models: exact triangle counts (from ../shared/data/README.md), format detection, units,
// gzip, and round trips through write_stl.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"

using namespace rosmill::core;

namespace {

struct Model {
  const char* dir;  // ROSMILL_TEST_DATA or ROSMILL_SHARED_DATA "/stl"
  const char* file;
  bool ascii;
  size_t triangles;
};

const Model kModels[] = {
    {ROSMILL_TEST_DATA, "failedinpycam.stl", true, 428},
    {ROSMILL_TEST_DATA, "pycam-textbox.stl", true, 1444},
    {ROSMILL_TEST_DATA, "featuretype.STL", false, 3476},
    {ROSMILL_TEST_DATA, "ktoolcav.stl", false, 4090},
    {ROSMILL_TEST_DATA, "wheel_in_box.stl", true, 6102},
    {ROSMILL_TEST_DATA, "mount_rush.stl", false, 15592},
    {ROSMILL_SHARED_DATA "/stl", "counter.unitsmm.STL", false, 83750},
    {ROSMILL_SHARED_DATA "/stl", "demo2.stl.gz", true, 146336},
};

bool exists(const std::string& path) { return ::access(path.c_str(), R_OK) == 0; }

std::string temp_path(const std::string& name) {
  return testing::TempDir() + "rosmill_test_stl_" + std::to_string(::getpid()) + "_" + name;
}

}  // namespace

TEST(Stl, EveryModelLoadsWithItsExactTriangleCount) {
  for (const Model& m : kModels) {
    const std::string path = std::string(m.dir) + "/" + m.file;
    if (!exists(path)) {
      std::printf("skipping %s: not present (a large model kept only in ../shared/data)\n", path.c_str());
      continue;
    }
    SCOPED_TRACE(path);
    StlInfo info;
    const Mesh mesh = read_stl(path, {}, &info);
    EXPECT_EQ(mesh.face_count(), m.triangles);
    EXPECT_EQ(info.ascii, m.ascii);
    EXPECT_EQ(mesh.normals.size(), m.triangles);
    EXPECT_EQ(mesh.face_edges.size(), m.triangles);
    // Welding shares corners: an indexed surface has far fewer vertices than corners.
    EXPECT_GT(mesh.vertex_count(), 2u);
    EXPECT_LT(mesh.vertex_count(), 3 * m.triangles);
    EXPECT_FALSE(mesh.bbox.empty());
  }
}

TEST(Stl, Demo2FromSharedData) {
  const std::string path = ROSMILL_SHARED_DATA "/stl/demo2.stl.gz";
  if (!exists(path)) GTEST_SKIP() << path << " is absent (only in ../shared/data)";
  StlInfo info;
  const Mesh mesh = read_stl(path, {}, &info);
  EXPECT_EQ(mesh.face_count(), 146336u);
  EXPECT_TRUE(info.ascii);
  const Vec3 size = mesh.bbox.size();
  EXPECT_NEAR(size.x(), 152, 1.0);
  EXPECT_NEAR(size.y(), 148, 1.0);
  EXPECT_NEAR(size.z(), 50, 1.0);
}

TEST(Stl, BinaryWithSolidHeaderIsReadAsBinary) {
  // ktoolcav.stl's 80-byte header starts with "solid": its size, not its first word, makes it binary.
  StlInfo info;
  const Mesh mesh = read_stl(ROSMILL_TEST_DATA "/ktoolcav.stl", {}, &info);
  EXPECT_FALSE(info.ascii);
  EXPECT_EQ(mesh.face_count(), 4090u);
  const Vec3 size = mesh.bbox.size();  // 4 x 1.62 x 3.31 inch
  EXPECT_NEAR(size.x(), 4.0, 0.05);
  EXPECT_NEAR(size.y(), 1.62, 0.05);
  EXPECT_NEAR(size.z(), 3.31, 0.05);
}

TEST(Stl, UnitsScaleToMillimetres) {
  const Mesh inch = read_stl(ROSMILL_TEST_DATA "/featuretype.STL");
  StlReadOptions options;
  options.units = Units::Inch;
  const Mesh mm = read_stl(ROSMILL_TEST_DATA "/featuretype.STL", options);
  ASSERT_EQ(inch.vertex_count(), mm.vertex_count());
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(mm.bbox.min[k], 25.4 * inch.bbox.min[k], 1e-9);
    EXPECT_NEAR(mm.bbox.max[k], 25.4 * inch.bbox.max[k], 1e-9);
  }
  EXPECT_NEAR(report(mm).area, 25.4 * 25.4 * report(inch).area, 1e-6 * report(mm).area);
  options.units = Units::Metre;
  const Mesh metre = read_stl(ROSMILL_TEST_DATA "/featuretype.STL", options);
  EXPECT_NEAR(metre.bbox.max.x(), 1000.0 * inch.bbox.max.x(), 1e-9);
}

TEST(Stl, GzipIsRecognisedByContent) {
  // A gzip-compressed copy under a plain .stl name still loads: the magic bytes decide.
  const std::string plain = ROSMILL_TEST_DATA "/failedinpycam.stl";
  const std::string packed = temp_path("failedinpycam_gz.stl");
  ASSERT_EQ(std::system(("gzip -c '" + plain + "' > '" + packed + "'").c_str()), 0);
  const Mesh a = read_stl(plain);
  const Mesh b = read_stl(packed);
  std::remove(packed.c_str());
  EXPECT_EQ(b.face_count(), 428u);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.faces, b.faces);
}

TEST(Stl, BinaryRoundTripKeepsFloatCornersExactly) {
  const Mesh original = read_stl(ROSMILL_TEST_DATA "/mount_rush.stl");
  const std::string path = temp_path("round.stl");
  write_stl(path, original, false);
  StlInfo info;
  const Mesh back = read_stl(path, {}, &info);
  std::remove(path.c_str());
  EXPECT_FALSE(info.ascii);
  EXPECT_EQ(info.stored_normal_mismatches, 0u);
  EXPECT_EQ(back.faces, original.faces);
  EXPECT_EQ(back.vertices, original.vertices);  // corners were float32 already: bit-exact
}

TEST(Stl, AsciiRoundTripKeepsDoublesExactly) {
  const Mesh original = make_primitive("dome");
  const std::string path = temp_path("round_ascii.stl");
  write_stl(path, original, true);
  StlInfo info;
  const Mesh back = read_stl(path, {}, &info);
  std::remove(path.c_str());
  EXPECT_TRUE(info.ascii);
  EXPECT_EQ(info.solids, 1u);
  EXPECT_EQ(info.stored_normal_mismatches, 0u);
  EXPECT_EQ(back.faces, original.faces);
  EXPECT_EQ(back.vertices, original.vertices);
  const MeshReport r = report(back);
  EXPECT_TRUE(r.closed);
  EXPECT_NEAR(r.volume, report(original).volume, 1e-9);
}
