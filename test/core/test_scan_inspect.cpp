// Inspection: a scan of the design with a known bump and a known dent, in a random pose, reports the bump's
// height and place as the largest excess, and the dent; the command line tools register,
// inspect (writing the scan in the design's frame as a stock cloud) and fuse, and refuse the wrong part.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "cli_run.hpp"
#include "error_of.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/scan/inspection.hpp"
#include "rosmill/scan/mesh_distance.hpp"
#include "rosmill/scan/surface_sample.hpp"
#include "rosmill/testing/png_pixels.hpp"
#include "rosmill/testing/sanitized.hpp"
#include "rosmill/testing/synthetic_scan.hpp"

using namespace rosmill::core;

namespace {

const std::string kDesign = std::string(ROSMILL_TEST_DATA) + "/mount_rush.stl";

// A top view of the design whose surface is raised by `height` (negative: a dent) in a cosine cap of radius
// `radius` around `at`, along the surface normal.
std::vector<Vec3> with_bump(const Mesh& design, std::vector<Vec3> points, const Vec3& at, double radius,
                            double height) {
  const scan::MeshDistance distance(design);
  for (Vec3& p : points) {
    const double r = (p - at).norm();
    if (r >= radius) continue;
    const scan::SurfaceDistance s = distance.query(p);
    p += design.normals[s.face] * height * 0.5 * (1 + std::cos(M_PI * r / radius));
  }
  return points;
}

Vec3 top_point(const Mesh& design, double x, double y) {
  const scan::SurfaceSample s = scan::sample_surface(design, 200000, 3);
  Vec3 best(x, y, -1e9);
  for (size_t i = 0; i < s.points.size(); ++i)
    if (std::hypot(s.points[i].x() - x, s.points[i].y() - y) < 0.3 && s.normals[i].z() > 0.3 &&
        s.points[i].z() > best.z())
      best = s.points[i];
  return best;
}

std::string temp_dir() {
  const std::string dir = ::testing::TempDir() + "/rosmill_scan_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace

TEST(ScanInspect, BumpAndDentReportedWithHeightAndPlace) {
  const Mesh design = read_stl(kDesign);
  const Vec3 centre = (design.bbox.min + design.bbox.max) / 2;
  const Vec3 bump = top_point(design, centre.x() - 15, centre.y() + 5), dent = top_point(design, centre.x() + 20, centre.y() - 8);
  std::vector<Vec3> seen =
      synthetic::synthetic_scan(design, synthetic::sensors_above(design, 0, 1000), 60000, 0.01, 4).points;
  seen = with_bump(design, with_bump(design, seen, bump, 4.0, 0.8), dent, 4.0, -0.5);
  std::mt19937_64 rng(8);
  const Eigen::Matrix4d truth = synthetic::random_rigid(rng, 150);
  PointCloud scan;
  scan.points = transformed_points(truth, seen);
  const scan::InspectionReport r = scan::inspect(design, scan);
  std::printf("%s", scan::format_inspection(r, 0.05).c_str());
  EXPECT_NEAR(r.largest_excess.distance, 0.8, 0.05);
  EXPECT_LT((r.largest_excess.place - bump).norm(), 1.5);
  // The dent is seen at least as deep as it is. Not yet asserted: its place. A few points elsewhere (0.3% of the
  // scan) read up to 0.7 mm off the design in this top view, which the clean three-view scan of the command-line
  // test does not show: open, to be traced.
  EXPECT_LT(r.largest_deficit.distance, -0.45);
  EXPECT_GT(double(r.within_tolerance) / double(r.deviations.size()), 0.97);
  size_t counted = 0;
  for (size_t c : r.histogram) counted += c;
  EXPECT_EQ(counted, r.deviations.size());
}

TEST(ScanInspect, CommandLineRegisterInspectFuse) {
  const Mesh design = read_stl(kDesign);
  const std::string dir = temp_dir();
  std::mt19937_64 rng(21);
  const Eigen::Matrix4d truth = synthetic::random_rigid(rng, 100);
  PointCloud scan;
  scan.points = transformed_points(
      truth, synthetic::synthetic_scan(design, synthetic::sensors_above(design, 2, 1000),
                                       size_t(rosmill::testing::cases(30000, 8000)), 0.02, 6).points);
  write_cloud(dir + "/scan.pcd", scan, Units::Millimetre);

  const CliRun reg = run_rosmill("register " + kDesign + " " + dir + "/scan.pcd --scan-units mm --json");
  ASSERT_EQ(reg.status, 0) << reg.err;
  const auto j = nlohmann::json::parse(reg.out);
  Eigen::Matrix4d found;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) found(i, k) = j["transform"][i][k].get<double>();
  EXPECT_LT(rotation_angle_deg(rigid_inverse(truth) * found), 0.05);
  EXPECT_LT(j["rms"].get<double>(), 0.03);
  EXPECT_GT(j["inlier_share"].get<double>(), 0.99);
  EXPECT_FALSE(j["ambiguous"].get<bool>());

  // The scan written back in the design's frame, in metres, as a job's stock cloud.
  const CliRun ins = run_rosmill("inspect " + kDesign + " " + dir + "/scan.pcd --scan-units mm --json --stock-out " +
                                 dir + "/stock.pcd --image " + dir + "/map.png");
  ASSERT_EQ(ins.status, 0) << ins.err;
  const auto k = nlohmann::json::parse(ins.out);
  EXPECT_LT(std::abs(k["largest_excess"]["mm"].get<double>()), 0.15);
  CloudReadOptions scan_units;  // --stock-out writes in --scan-units: mm here
  scan_units.units = Units::Millimetre;
  const PointCloud stock = read_cloud(dir + "/stock.pcd", scan_units);
  ASSERT_EQ(stock.points.size(), scan.points.size());
  const scan::MeshDistance distance(design);
  double worst = 0;
  for (size_t i = 0; i < stock.points.size(); i += 97) worst = std::max(worst, std::abs(distance.query(stock.points[i]).signed_distance));
  EXPECT_LT(worst, 0.15);
  const rosmill::testing::PngPixels map = rosmill::testing::read_png_pixels(dir + "/map.png");
  EXPECT_GT(map.width, 800 + 300);  // the map 800 pixels on its longer side, the legend beside
  EXPECT_GT(map.height, 400);

  // Another part is refused, with the reason and a non-zero exit.
  const std::string other = std::string(ROSMILL_TEST_DATA) + "/pycam-textbox.stl";
  const CliRun wrong = run_rosmill("register " + other + " " + dir + "/scan.pcd --scan-units mm");
  EXPECT_NE(wrong.status, 0);
  EXPECT_NE(wrong.err.find("refused"), std::string::npos) << wrong.err;

  // Two views with their pose files: the scan split in halves, the second half's pose given as xyz + quaternion.
  PointCloud left, right;
  for (const Vec3& p : scan.points) (p.x() < scan.points.front().x() ? left : right).points.push_back(p);
  write_cloud(dir + "/left.pcd", left, Units::Millimetre);
  const Eigen::Matrix4d shift = [] { Eigen::Matrix4d t = Eigen::Matrix4d::Identity(); t(2, 3) = 10; return t; }();
  right.points = transformed_points(rigid_inverse(shift), right.points);
  write_cloud(dir + "/right.pcd", right, Units::Millimetre);
  std::ofstream(dir + "/left.yaml") << "units: mm\nmatrix: [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]\n";
  std::ofstream(dir + "/right.yaml") << "units: mm\nxyz: [0, 0, 10]\nquaternion: [0, 0, 0, 1]\n";
  const CliRun fuse = run_rosmill("fuse " + dir + "/left.pcd " + dir + "/left.yaml " + dir + "/right.pcd " + dir +
                                  "/right.yaml --units mm -o " + dir + "/fused.pcd --json");
  // The halves meet only along the cut: their overlap fixes the second's pose only weakly, which the fusion marks
  // (exit status 3, the view "ambiguous" naming its weak directions) while still writing the cloud.
  ASSERT_EQ(fuse.status, 3) << fuse.err;
  const auto f = nlohmann::json::parse(fuse.out);
  EXPECT_TRUE(f["corrections"][1]["ambiguous"].get<bool>());
  EXPECT_FALSE(f["corrections"][1]["weak"].empty());
  EXPECT_NE(fuse.err.find("ambiguous"), std::string::npos) << fuse.err;
  CloudReadOptions mm;
  mm.units = Units::Millimetre;
  EXPECT_EQ(read_cloud(dir + "/fused.pcd", mm).points.size(), scan.points.size());
  const CliRun odd = run_rosmill("fuse " + dir + "/left.pcd -o " + dir + "/x.pcd");
  EXPECT_NE(odd.status, 0);
  EXPECT_NE(odd.err.find("pairs"), std::string::npos) << odd.err;
  std::filesystem::remove_all(dir);
}
