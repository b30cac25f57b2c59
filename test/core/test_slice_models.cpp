// Slicing the real models: every contour closed on every closed model, open chains exactly where the mesh is
// open (as few as its open and non-manifold edges allow), and the `rosmill slice` command.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "rosmill/io/stl.hpp"
#include "rosmill/slice/slicer.hpp"

using namespace rosmill::core;

namespace {

std::string test_file(const std::string& name) { return std::string(ROSMILL_TEST_DATA) + "/" + name; }
std::string shared_file(const std::string& name) { return std::string(ROSMILL_SHARED_DATA) + "/stl/" + name; }

// A chain can only end at a crossing edge of odd face count (an open edge, or the odd face out of a
// non-manifold fan): the fewest open chains a plane allows is half the number of such edges.
size_t forced_chain_ends(const Mesh& m, double h, bool from_above) {
  size_t ends = 0;
  for (const MeshEdge& e : m.edges) {
    const double za = m.vertices[e.a].z(), zb = m.vertices[e.b].z();
    const bool a_above = from_above ? za > h : za >= h, b_above = from_above ? zb > h : zb >= h;
    if (a_above != b_above && e.face_count % 2 == 1) ++ends;
  }
  return ends;
}

void expect_minimal_chains(const Mesh& m, const std::vector<SliceLayer>& layers, const std::string& name) {
  for (const SliceLayer& l : layers) {
    size_t open = 0;
    for (const Contour& c : l.contours) open += !c.closed;
    EXPECT_EQ(2 * open, forced_chain_ends(m, l.z, l.z <= m.bbox.min.z())) << name << " z = " << l.z;
  }
}

// Closed contours nest properly: a hole's parent is an outer contour and an outer's parent is a hole; outer
// contours run counter-clockwise and holes clockwise.
void expect_consistent_nesting(const SliceLayer& l, const std::string& name) {
  for (const Contour& c : l.contours) {
    if (!c.closed) continue;
    EXPECT_GT(c.area, 0.0) << name;
    EXPECT_EQ(signed_area(c.points) > 0, !c.hole) << name << " z = " << l.z;
    if (c.hole) {
      ASSERT_GE(c.parent, 0) << name << " a hole outside every contour at z = " << l.z;
      EXPECT_FALSE(l.contours[size_t(c.parent)].hole) << name;
    } else if (c.parent >= 0) {
      EXPECT_TRUE(l.contours[size_t(c.parent)].hole) << name;
    }
  }
}

void check_model(const std::string& path, const std::string& name) {
  const Mesh m = read_stl(path);
  std::vector<double> planes = planes_by_count(m, 60);
  planes.push_back(m.bbox.min.z());
  planes.push_back(m.bbox.max.z());
  const std::vector<SliceLayer> layers = slice_mesh(m, planes);
  const SliceSummary s = summarize(layers);
  EXPECT_GT(s.contours, 0u) << name;
  if (m.closed()) {
    EXPECT_EQ(s.open_contours, 0u) << name << " is closed: every contour must be closed";
  }
  expect_minimal_chains(m, layers, name);
  for (const SliceLayer& l : layers) expect_consistent_nesting(l, name);
}

}  // namespace

TEST(SliceModels, EveryContourClosedOnTheClosedModels) {
  for (const char* name : {"failedinpycam.stl", "pycam-textbox.stl", "ktoolcav.stl", "wheel_in_box.stl"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(read_stl(test_file(name)).closed()) << name;
    check_model(test_file(name), name);
  }
}

TEST(SliceModels, OpenFeatureTypeGivesOpenChainsOnlyAtItsOpenEdges) {
  // featuretype.STL has open edges (576 of them, welded exactly): its open chains are exactly the forced ones.
  ASSERT_FALSE(read_stl(test_file("featuretype.STL")).closed());
  check_model(test_file("featuretype.STL"), "featuretype.STL");
}

TEST(SliceModels, CounterIsClosedEverywhere) {
  const std::string path = shared_file("counter.unitsmm.STL");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not present";
  check_model(path, "counter.unitsmm.STL");
  const Mesh m = read_stl(path);
  const SliceSummary s = summarize(slice_mesh(m, planes_by_step(m, 0.1)));
  EXPECT_EQ(s.layers, 258u);
  EXPECT_EQ(s.open_contours, 0u);
}

TEST(SliceModels, NonManifoldMountRushHasOnlyTheChainsItsTopologyForces) {
  const Mesh m = read_stl(test_file("mount_rush.stl"));
  ASSERT_FALSE(m.closed());
  size_t nonmanifold = 0;
  for (const MeshEdge& e : m.edges) nonmanifold += e.nonmanifold();
  ASSERT_GT(nonmanifold, 0u);
  const auto layers = slice_mesh(m, planes_by_step(m, 0.1));
  expect_minimal_chains(m, layers, "mount_rush.stl");
  for (const SliceLayer& l : layers) expect_consistent_nesting(l, "mount_rush.stl");
}

TEST(SliceModels, Demo2OpenEdgesGiveOpenChainsOnly) {
  const std::string path = shared_file("demo2.stl.gz");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not present";
  const Mesh m = read_stl(path);
  const auto layers = slice_mesh(m, planes_by_count(m, 50));
  expect_minimal_chains(m, layers, "demo2");
}

namespace {

int run_cli(const std::string& args, std::string& out) {
  FILE* pipe = ::popen((std::string(ROSMILL_CLI) + " " + args + " 2>/dev/null").c_str(), "r");
  if (!pipe) return -1;
  char buf[4096];
  out.clear();
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  return WEXITSTATUS(::pclose(pipe));
}

}  // namespace

TEST(SliceModels, CommandPrintsTheIssuesJsonAndWritesTheDatFile) {
  const std::string dat = ::testing::TempDir() + "slice_cli.dat";
  std::string out;
  ASSERT_EQ(run_cli("slice " + test_file("wheel_in_box.stl") + " --layers 7 --json --out " + dat, out), 0);
  const auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j.at("layers"), 7);
  ASSERT_EQ(j.at("layers_detail").size(), 7u);
  size_t contours = 0, points = 0;
  for (const auto& l : j.at("layers_detail")) {
    EXPECT_TRUE(l.contains("z") && l.contains("flat_area"));
    for (const auto& c : l.at("contours")) {
      ++contours;
      points += c.at("points").get<size_t>();
      EXPECT_TRUE(c.at("closed").get<bool>());
      EXPECT_GT(c.at("area").get<double>(), 0.0);
      EXPECT_TRUE(c.contains("hole") && c.contains("parent"));
    }
  }
  EXPECT_EQ(j.at("contours").get<size_t>(), contours);
  EXPECT_EQ(j.at("points").get<size_t>(), points);
  EXPECT_EQ(j.at("open_contours"), 0);
  EXPECT_GE(j.at("seconds").get<double>(), 0.0);
  // The .dat file: a block per contour, each closed contour's first point repeated at its end.
  std::ifstream in(dat);
  std::string line;
  size_t rows = 0, blocks = 1;
  while (std::getline(in, line)) line.empty() ? ++blocks : ++rows;
  EXPECT_EQ(blocks, contours);
  EXPECT_EQ(rows, points + contours);

  ASSERT_EQ(run_cli("slice " + test_file("ktoolcav.stl") + " --z 0.5,-1,1.25 --json", out), 0);
  const auto k = nlohmann::json::parse(out);
  EXPECT_EQ(k.at("layers_detail").at(0).at("z"), -1.0);
  EXPECT_EQ(k.at("layers_detail").at(2).at("z"), 1.25);

  EXPECT_EQ(run_cli("slice " + test_file("ktoolcav.stl") + " --z 1,x", out), 1);
  EXPECT_EQ(run_cli("slice " + test_file("ktoolcav.stl") + " --step 0.1 --layers 3", out), 1);
  EXPECT_EQ(run_cli("slice " + test_file("ktoolcav.stl") + " --step -1", out), 1);
  EXPECT_EQ(run_cli("slice " + test_file("ktoolcav.stl"), out), 1);
  EXPECT_EQ(run_cli("slice /nonexistent.stl --layers 3", out), 1);
}
