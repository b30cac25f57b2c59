// Large STL files take the parallel paths (ASCII in chunks from 4 MB, binary welded in two halves from 200,000
// triangles): they must give exactly what one sequential pass gives — the same vertices in the same order, the
// same faces, solids and errors (with the same line or triangle named).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/heap_reuse.hpp"
#include "rosmill/testing/wavy_solid.hpp"
#include "rosmill/io/stl.hpp"

using namespace rosmill::core;

namespace {

std::string temp_path(const std::string& name) {
  return testing::TempDir() + "rosmill_test_stl_large_" + std::to_string(::getpid()) + "_" + name;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The sequential reference: one welder pass over the corners as the file stores them.
Mesh one_pass(const std::vector<Vec3>& corners) { return build_mesh(corners); }

void expect_same_mesh(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  ASSERT_EQ(a.faces.size(), b.faces.size());
  for (size_t i = 0; i < a.vertices.size(); ++i) ASSERT_EQ(a.vertices[i], b.vertices[i]) << "vertex " << i;
  for (size_t f = 0; f < a.faces.size(); ++f) ASSERT_EQ(a.faces[f], b.faces[f]) << "face " << f;
  EXPECT_EQ(a.edges.size(), b.edges.size());
}

std::string read_error(const std::string& path) {
  try {
    read_stl(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(StlLarge, AsciiInChunksEqualsOnePass) {
  const Mesh wavy = build_mesh(wavy_solid_corners(120, 200.0));  // 30,240 triangles: about 8 MB of text
  const std::string path = temp_path("wavy.stl");
  write_stl(path, wavy, true);
  const std::string text = slurp(path);
  ASSERT_GE(text.size(), size_t(4) << 20) << "too small to take the chunked path";
  StlInfo info;
  const Mesh read = read_stl(path, {}, &info);
  EXPECT_TRUE(info.ascii);
  EXPECT_EQ(info.solids, 1u);
  EXPECT_TRUE(read.closed());
  expect_same_mesh(read, wavy);  // ASCII round trips keep doubles exactly
  // Two solids in one large file: both read, counted, in order.
  std::ofstream(path, std::ios::binary) << text << text;
  const Mesh twice = read_stl(path, {}, &info);
  EXPECT_EQ(info.solids, 2u);
  EXPECT_EQ(twice.face_count(), 2 * wavy.face_count());
  EXPECT_EQ(twice.vertex_count(), wavy.vertex_count());  // the second solid's corners weld onto the first's
  std::remove(path.c_str());
}

TEST(StlLarge, AsciiErrorsNameTheSameLineAsOnePass) {
  const Mesh wavy = build_mesh(wavy_solid_corners(120, 200.0));
  const std::string path = temp_path("broken.stl");
  write_stl(path, wavy, true);
  std::string text = slurp(path);
  // Break a number three quarters into the file (inside a later chunk) and find its line.
  const size_t at = text.find("vertex", text.size() * 3 / 4) + 7;
  text[at] = 'x';
  const long line = 1 + std::count(text.begin(), text.begin() + at, '\n');
  std::ofstream(path, std::ios::binary) << text;
  const std::string msg = read_error(path);
  EXPECT_NE(msg.find(path + ":" + std::to_string(line) + ":"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected a number"), std::string::npos) << msg;
  // A large file cut short: the solid is not closed.
  std::ofstream(path, std::ios::binary) << text.substr(0, text.size() / 2);
  EXPECT_NE(read_error(path).find("truncated"), std::string::npos) << read_error(path);
  // A facet outside any solid, in the middle of the file.
  text = slurp(path);  // (the half file)
  std::string body = text.substr(text.find("facet"));
  std::ofstream(path, std::ios::binary) << "solid a\nendsolid a\n" << body << body;
  EXPECT_NE(read_error(path), "") << "facets after endsolid must be refused";
  std::remove(path.c_str());
}

TEST(StlLarge, BinaryWeldedInHalvesEqualsOnePass) {
  const std::vector<Vec3> corners = wavy_solid_corners(320, 200.0);  // 208,640 triangles
  const std::string path = temp_path("wavy.bin.stl");
  write_stl(path, build_mesh(corners), false);
  std::vector<Vec3> stored(corners.size());  // the file holds float32 corners
  for (size_t i = 0; i < corners.size(); ++i) stored[i] = corners[i].cast<float>().cast<double>();
  StlInfo info;
  const Mesh read = read_stl(path, {}, &info);
  EXPECT_FALSE(info.ascii);
  EXPECT_EQ(info.stored_normal_mismatches, 0u);
  EXPECT_TRUE(read.closed());
  expect_same_mesh(read, one_pass(stored));
  std::remove(path.c_str());
}

TEST(StlLarge, BinaryErrorNamesTheFirstBadTriangle) {
  const Mesh wavy = build_mesh(wavy_solid_corners(320, 200.0));
  const std::string path = temp_path("nan.bin.stl");
  write_stl(path, wavy, false);
  std::string bytes = slurp(path);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (size_t t : {size_t(150000), size_t(190000)})  // both in the second half; the first must be named
    std::memcpy(&bytes[84 + 50 * t + 12], &nan, sizeof nan);
  std::ofstream(path, std::ios::binary) << bytes;
  const std::string msg = read_error(path);
  EXPECT_NE(msg.find("triangle 150000 "), std::string::npos) << msg;
  EXPECT_NE(msg.find("not finite"), std::string::npos) << msg;
  std::remove(path.c_str());
}

// The binary reader faults a large face array in on both cores before filling it. Faulting in is only about
// pages: on a block large enough to be split (32 MB, its ends not on page boundaries), the words already written
// keep their values, and the block is then filled as usual.
TEST(HeapReuse, FaultingInKeepsWrittenWords) {
  std::vector<uint32_t> block;
  block.reserve((size_t(32) << 20) / sizeof(uint32_t) + 3);
  block.resize(block.capacity() / 2);
  for (size_t i = 0; i < block.size(); ++i) block[i] = uint32_t(i * 2654435761u);
  fault_in_on_both_cores(block.data() + 1, block.capacity() * sizeof(uint32_t) - 7);
  for (size_t i = 0; i < block.size(); ++i) ASSERT_EQ(block[i], uint32_t(i * 2654435761u)) << "word " << i;
  block.resize(block.capacity(), 7u);
  EXPECT_EQ(block.back(), 7u);
}
