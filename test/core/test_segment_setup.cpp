// Phase 2 of the segmentation (EGI, setup filters, pruning), coverage, and the `rosmill segment` command.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/segment/coverage.hpp"
#include "rosmill/segment/setup_segmentation.hpp"

using namespace rosmill::core;
using namespace rosmill::core::segment;

namespace {

// A torus (R 40, r 15) of nu x nv quads, axis Z: one smooth closed patch.
Mesh torus(int nu, int nv) {
  auto p = [&](int i, int j) {
    const double u = 2 * M_PI * (i % nu) / nu, v = 2 * M_PI * (j % nv) / nv;
    return Vec3((40 + 15 * std::cos(v)) * std::cos(u), (40 + 15 * std::cos(v)) * std::sin(u), 15 * std::sin(v));
  };
  std::vector<Vec3> c;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      for (const Vec3& q : {p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j), p(i + 1, j + 1), p(i, j + 1)})
        c.push_back(q);
  return build_mesh(c);
}

double area_facing(const Mesh& m, const std::vector<uint8_t>& reach, const Vec3& n, bool reached) {
  double a = 0;
  for (size_t f = 0; f < m.face_count(); ++f)
    if (bool(reach[f]) == reached && m.normals[f].dot(n) > 0.999) a += m.areas[f];
  return a;
}

}  // namespace

TEST(SegmentEgi, BinsHaveNearlyEqualAreaAndCoverTheSphere) {
  const EgiBins bins;
  double total = 0, lo = 1e9, hi = 0;
  for (uint32_t b = 0; b < bins.size(); ++b) {
    total += bins.solid_angle(b);
    lo = std::min(lo, bins.solid_angle(b));
    hi = std::max(hi, bins.solid_angle(b));
    EXPECT_EQ(bins.bin_of(bins.centre(b)), b);
  }
  EXPECT_NEAR(total, 4 * M_PI, 1e-9);
  EXPECT_LT(hi / lo, 1.5);
  EXPECT_GT(bins.size(), 300u);
  // Every direction lies within its bin's radius of the bin's centre.
  for (int k = 0; k < 2000; ++k) {
    const double z = -1 + 2 * (k + 0.5) / 2000, a = 2.39996 * k;
    const Vec3 n(std::sqrt(1 - z * z) * std::cos(a), std::sqrt(1 - z * z) * std::sin(a), z);
    const uint32_t b = bins.bin_of(n);
    EXPECT_LE(std::acos(std::min(1.0, n.dot(bins.centre(b)))), bins.radius(b));
  }
}

// bin_of works without acos and atan2: it must pick the bin the plain definition gives (polar angle / ring
// step, azimuth from -pi / sector width) for every direction not within rounding of a border, and keep the
// normals of a flat face at a pole, whatever the signs of their zero components, in one bin.
TEST(SegmentEgi, BinOfAgreesWithThePolarAndAzimuthDefinition) {
  for (int rings : {1, 7, 18, 60}) {
    const EgiBins bins(rings);
    const double step = M_PI / rings;
    std::vector<uint32_t> first(rings + 1, uint32_t(bins.size()));  // first bin of each ring, from the centres
    for (uint32_t b = uint32_t(bins.size()); b-- > 0;) first[int(std::acos(bins.centre(b).z()) / step)] = b;
    uint32_t checked = 0;
    for (int k = 0; k < 200000; ++k) {
      const double z = -1 + 2 * (k + 0.5) / 200000, a = 2.39996322972865332 * k;
      const Vec3 n(std::sqrt(1 - z * z) * std::cos(a), std::sqrt(1 - z * z) * std::sin(a), z);
      const double polar = std::acos(z) / step, azimuth = std::atan2(n.y(), n.x()) + M_PI;
      const int ring = std::min(rings - 1, int(polar));
      const uint32_t sectors = first[ring + 1] - first[ring];
      const double sector = azimuth / (2 * M_PI) * sectors;
      if (std::abs(polar - std::round(polar)) < 1e-9 || std::abs(sector - std::round(sector)) < 1e-9) continue;
      ASSERT_EQ(bins.bin_of(n), first[ring] + std::min(sectors - 1, uint32_t(sector))) << n.transpose();
      ++checked;
    }
    EXPECT_GT(checked, 199000u);
    for (double sx : {0.0, -0.0})
      for (double sy : {0.0, -0.0}) {
        EXPECT_EQ(bins.bin_of(Vec3(sx, sy, 1.0)), bins.bin_of(Vec3(0, 0, 1)));
        EXPECT_EQ(bins.bin_of(Vec3(sx, sy, -1.0)), bins.bin_of(Vec3(0, 0, -1)));
      }
  }
}

// Directions exactly on a ring border (z = cos(r step) as computed) and one double either side: the ring is
// the number of borders strictly above z, for coarse and very fine bins (1000 rings: many borders share a
// lookup cell near the poles).
TEST(SegmentEgi, RingBordersAreExactAtTheBorderValues) {
  for (int rings : {7, 18, 1000}) {
    const EgiBins bins(rings);
    const double step = M_PI / rings;
    std::vector<double> border;
    for (int r = 1; r < rings; ++r) border.push_back(std::cos(r * step));
    for (int r = 1; r < rings; ++r)
      for (double z : {std::nextafter(border[r - 1], 2.0), border[r - 1], std::nextafter(border[r - 1], -2.0)}) {
        int expected = 0;
        for (double c : border) expected += z < c;
        const uint32_t b = bins.bin_of(Vec3(std::sqrt(std::max(0.0, 1 - z * z)), 0.0, z));
        ASSERT_EQ(int(std::acos(bins.centre(b).z()) / step), expected) << "rings " << rings << " z " << z;
      }
  }
}

TEST(SegmentEgi, PatchHistogramsHoldThePatchArea) {
  Mesh m = make_primitive("dome");
  const SurfacePatches sp = segment_surface(m);
  const EgiSet egis(sp);
  for (const Patch& p : sp.patches()) {
    double sum = 0;
    for (double a : egis.egi(p.id).areas) sum += a;
    EXPECT_NEAR(sum, p.area, 1e-9 * p.area);
  }
  // The flat base falls in one bin (-Z); the dome spreads over the upper hemisphere's bins.
  const Patch& base = sp.patch(sp.patches()[0].normal.z() < 0 ? 0 : 1);
  EXPECT_EQ(egis.egi(base.id).bins.size(), 1u);
  EXPECT_GT(egis.egi(1 - base.id).bins.size(), 100u);
}

TEST(SegmentSetup, PlusZOnTheCubeReachesTopAndSidesNotBottom) {
  Mesh m = make_primitive("cube");
  const SurfacePatches sp = segment_surface(m);
  const EgiSet egis(sp);
  const SetupSegmentation z = segment_setup(egis, parse_setup("+z"));
  EXPECT_NEAR(z.reachable_area(), 5 * 3600.0, 1e-9);
  EXPECT_NEAR(z.reachable_fraction(), 5.0 / 6.0, 1e-12);
  EXPECT_EQ(area_facing(m, z.reachable(), -Vec3::UnitZ(), true), 0.0);
  EXPECT_EQ(area_facing(m, z.reachable(), -Vec3::UnitZ(), false), 3600.0);
  for (const Vec3& side : std::vector<Vec3>{Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ()})
    EXPECT_EQ(area_facing(m, z.reachable(), side, true), 3600.0);
  ASSERT_EQ(z.count(), 6u);  // no face is cut: each is reachable or not as a whole
  int reachable = 0;
  for (const Segment& s : z.segments()) reachable += s.reachable;
  EXPECT_EQ(reachable, 5);
  EXPECT_GE(z.patches_decided_by_egi(), 2u);  // top and bottom need no per-facet test

  const SetupSegmentation five = segment_setup(egis, parse_setup("5axis"));
  EXPECT_NEAR(five.reachable_fraction(), 1.0, 1e-12);
  EXPECT_EQ(five.patches_decided_by_egi(), 6u);
}

TEST(SegmentSetup, FourAxisReachesAllAtNinetyDegreesButNotTheEndsAtSixty) {
  Mesh m = make_primitive("cube");
  const SurfacePatches sp = segment_surface(m);
  const EgiSet egis(sp);
  SetupFilter a = parse_setup("4axis:x");
  EXPECT_NEAR(segment_setup(egis, a).reachable_fraction(), 1.0, 1e-12);
  a.max_angle_deg = 60;  // the ends (normals along the rotary axis) are 90 degrees from every tool direction
  EXPECT_NEAR(segment_setup(egis, a).reachable_fraction(), 4.0 / 6.0, 1e-12);
}

TEST(SegmentSetup, PruningSplitsASmoothPatchIntoReachableAndUnreachableParts) {
  Mesh m = torus(96, 48);
  const SurfacePatches sp = segment_surface(m);
  ASSERT_EQ(sp.count(), 1u);
  const EgiSet egis(sp);
  const SetupSegmentation z = segment_setup(egis, parse_setup("+z"));
  EXPECT_EQ(z.patches_decided_by_egi(), 0u);
  ASSERT_EQ(z.count(), 2u);  // the upper and the lower half
  EXPECT_NE(z.segments()[0].reachable, z.segments()[1].reachable);
  EXPECT_NEAR(z.reachable_fraction(), 0.5, 0.03);
  for (const Segment& s : z.segments()) {
    EXPECT_EQ(s.patch, 0u);
    EXPECT_EQ(s.shape.loops.size(), 2u);  // each half of a torus is an annulus: inner and outer rim
    EXPECT_NEAR(s.reachable_area, s.reachable ? s.shape.area : 0.0, 1e-9 * s.shape.area);
  }
  // -X: the half facing -X (a different cut of the same patch).
  const SetupSegmentation x = segment_setup(egis, parse_setup("-x"));
  EXPECT_NEAR(x.reachable_fraction(), 0.5, 0.03);
  EXPECT_GE(x.count(), 2u);
}

TEST(SegmentSetup, SeveralSetupsCoexistOverOneUnchangedMesh) {
  Mesh m = make_primitive("cavity");
  const std::vector<Vec3> vertices = m.vertices;
  const std::vector<Vec3> normals = m.normals;
  const SurfacePatches sp = segment_surface(m);
  const std::vector<uint32_t> labels = sp.labels();
  const EgiSet egis(sp);
  std::vector<SetupSegmentation> all;
  for (const char* name : {"+z", "-x", "-z", "4axis:y", "5axis"}) all.push_back(segment_setup(egis, parse_setup(name)));
  EXPECT_EQ(&all[0].patches().mesh(), &m);
  EXPECT_EQ(&all[1].patches(), &sp);
  EXPECT_EQ(m.vertices, vertices);
  EXPECT_EQ(m.normals, normals);
  EXPECT_EQ(sp.labels(), labels);
  // Each keeps its own answer: +Z reaches the annulus, the wall and the pocket; -Z only the bottom and the wall.
  const double total = sp.total_area();
  const double bottom = area_facing(m, all[2].reachable(), -Vec3::UnitZ(), true);
  // The wall is reached by both, so the two areas add up to more than the part.
  EXPECT_GT(all[0].reachable_area() + all[2].reachable_area(), total);
  EXPECT_NEAR(all[0].reachable_area() + bottom, total, 1e-9 * total);
  EXPECT_EQ(area_facing(m, all[0].reachable(), -Vec3::UnitZ(), true), 0.0);
  EXPECT_GT(bottom, 0.0);
  EXPECT_NEAR(all[4].reachable_fraction(), 1.0, 1e-12);
  // -X cuts the pocket and the wall in two (the halves facing -X and +X).
  EXPECT_GT(all[1].count(), sp.count());
}

TEST(SegmentCoverage, CoverageAndGreedyCover) {
  Mesh m = make_primitive("cube");
  const SurfacePatches sp = segment_surface(m);
  const EgiSet egis(sp);
  EXPECT_NEAR(coverage(egis, parse_setups("+z")), 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(coverage(egis, parse_setups("+z,-z")), 1.0, 1e-12);
  EXPECT_NEAR(coverage(egis, {}), 0.0, 1e-12);
  std::vector<std::string> names;
  for (const SetupFilter& s : greedy_axis_cover(egis)) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"+z", "-z"}));

  // The cavity's pocket faces up and in: +Z reaches all but the bottom, which -Z adds.
  Mesh cav = make_primitive("cavity");
  const SurfacePatches csp = segment_surface(cav);
  const EgiSet cegis(csp);
  names.clear();
  for (const SetupFilter& s : greedy_axis_cover(cegis)) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"+z", "-z"}));
  EXPECT_NEAR(coverage(cegis, greedy_axis_cover(cegis)), 1.0, 1e-12);
}

TEST(SegmentSetup, ParsesSetupNamesAndRejectsOthers) {
  EXPECT_EQ(parse_setup("-x").axis, -Vec3::UnitX());
  EXPECT_EQ(parse_setup("+Z").name, "+z");
  EXPECT_EQ(parse_setup("4axis:y").kind, SetupFilter::Kind::FourAxis);
  EXPECT_EQ(parse_setup("5axis").kind, SetupFilter::Kind::FiveAxis);
  EXPECT_EQ(parse_setups("+z,-x,5axis").size(), 3u);
  for (const char* bad : {"", "+w", "z", "4axis:q", "3axis", "+z,"}) EXPECT_THROW(parse_setups(bad), Error) << bad;
}

namespace {

std::string run_cli(const std::string& args, int* status) {
  const std::string cmd = std::string(ROSMILL_CLI) + " " + args + " 2>/dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  *status = pclose(pipe);
  return out;
}

}  // namespace

TEST(SegmentCli, JsonHasExactlyTheIssuesShape) {
  const std::string path = ::testing::TempDir() + "/segment_cube.stl";
  write_stl(path, make_primitive("cube"));
  int status = 0;
  const std::string out = run_cli("segment " + path + " --setup +z,-x,5axis --json", &status);
  ASSERT_EQ(status, 0) << out;
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(out);
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"count", "patches", "setups", "cover"}));
  EXPECT_EQ(j["count"], 6);
  ASSERT_EQ(j["patches"].size(), 6u);
  for (const auto& p : j["patches"]) {
    std::vector<std::string> pk;
    for (auto it = p.begin(); it != p.end(); ++it) pk.push_back(it.key());
    EXPECT_EQ(pk, (std::vector<std::string>{"id", "facets", "area", "normal", "neighbours"}));
    EXPECT_EQ(p["facets"], 2);
    EXPECT_NEAR(p["area"].get<double>(), 3600.0, 1e-9);
    EXPECT_EQ(p["neighbours"].size(), 4u);
  }
  ASSERT_EQ(j["setups"].size(), 3u);
  for (const auto& s : j["setups"]) {
    std::vector<std::string> sk;
    for (auto it = s.begin(); it != s.end(); ++it) sk.push_back(it.key());
    EXPECT_EQ(sk, (std::vector<std::string>{"name", "reachable_area", "reachable_fraction", "segments"}));
  }
  EXPECT_EQ(j["setups"][0]["name"], "+z");
  EXPECT_NEAR(j["setups"][0]["reachable_area"].get<double>(), 18000.0, 1e-6);
  EXPECT_NEAR(j["setups"][0]["reachable_fraction"].get<double>(), 5.0 / 6.0, 1e-12);
  EXPECT_EQ(j["setups"][0]["segments"], 6);
  EXPECT_EQ(j["setups"][1]["name"], "-x");
  EXPECT_NEAR(j["setups"][2]["reachable_fraction"].get<double>(), 1.0, 1e-12);
  EXPECT_EQ(j["cover"], nlohmann::ordered_json({"+z", "-z"}));

  // Bad input: an unknown setup and exclusive size rules fail with a non-zero status.
  run_cli("segment " + path + " --setup +q --json", &status);
  EXPECT_NE(status, 0);
  run_cli("segment " + path + " --min-facets 3 --min-area-fraction 0.1", &status);
  EXPECT_NE(status, 0);
  run_cli("segment " + path + " --threshold 3", &status);
  EXPECT_NE(status, 0);
  // --min-facets 3 merges the cube's two-facet faces into one patch.
  const nlohmann::json merged = nlohmann::json::parse(run_cli("segment " + path + " --min-facets 3 --json", &status));
  EXPECT_EQ(merged["count"], 1);
}
