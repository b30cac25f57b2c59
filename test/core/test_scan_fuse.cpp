// Multi-view fusion: three partial views of a relief, taken from three sides with poses that are off by a
// millimetre and half a degree, fuse into one cloud whose distance to the design is the sensor noise; sensor
// pose files in both forms; bad views refused with the reason.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>

#include "error_of.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/scan/mesh_distance.hpp"
#include "rosmill/scan/pose_file.hpp"
#include "rosmill/scan/view_fusion.hpp"
#include "rosmill/testing/ply_mesh.hpp"
#include "rosmill/testing/pose_error.hpp"
#include "rosmill/testing/sanitized.hpp"
#include "rosmill/testing/synthetic_scan.hpp"

using namespace rosmill::core;

namespace {

// Prints each direction's true error beside its stated 3 sigma; counts the directions not named weak whose error
// is over it ("wrong and said certain").
size_t wrong_and_certain_directions(const scan::PoseInformation& information, const std::array<double, 6>& error) {
  size_t wrong = 0;
  std::printf("  true error / stated 3 sigma per direction:");
  for (size_t k = 0; k < 6; ++k) {
    const scan::PoseDirection& d = information.dofs[k];
    std::printf(" %.4f/%.4f%s", std::abs(error[k]), 3 * d.sigma, d.weak ? "(weak)" : "");
    wrong += !d.weak && std::abs(error[k]) > 3 * d.sigma;
  }
  return wrong;
}

// Three views of the relief from around it, 120 degrees apart and 56 degrees up, each in its sensor's frame;
// the second and third with poses nudged by 1 mm and 0.5 degree. (Views that overlap only in planes, such as a
// cube's faces, leave a slide free that no registration can fix.)
std::vector<scan::ScanView> relief_views(const Mesh& relief) {
  const Vec3 centre = (relief.bbox.min + relief.bbox.max) / 2;
  std::vector<scan::ScanView> views;
  for (int i = 0; i < 3; ++i) {
    const double a = 2 * M_PI * i / 3;
    const Vec3 position = centre + 400 * Vec3(std::cos(a), std::sin(a), 1.5).normalized();
    const Eigen::Matrix4d pose = synthetic::sensor_pose(position, centre);
    scan::ScanView v;
    v.cloud.points = transformed_points(rigid_inverse(pose), synthetic::synthetic_scan(relief, {position}, 20000, 0.02,
                                                                                      uint64_t(11 + i)).points);
    v.pose = i == 0 ? pose : Eigen::Matrix4d(synthetic::nudge(1.0, 0.5, Vec3(1, -2, i)) * pose);
    v.name = "relief " + std::to_string(i);
    views.push_back(v);
  }
  return views;
}

double rms_to(const Mesh& design, const PointCloud& cloud, double* worst) {
  const scan::MeshDistance distance(design);
  const std::vector<double> d = distance.distances(cloud.points);
  double sum = 0;
  for (double x : d) sum += x * x;
  *worst = *std::max_element(d.begin(), d.end());
  return std::sqrt(sum / double(d.size()));
}

}  // namespace

TEST(ScanFuse, ThreePerturbedViewsFuseWithinNoise) {
  const Mesh relief = read_stl(std::string(ROSMILL_TEST_DATA) + "/mount_rush.stl");
  const std::vector<scan::ScanView> views = relief_views(relief);
  scan::FusionReport report;
  const PointCloud fused = scan::fuse_views(views, {}, &report);
  double worst = 0;
  const double rms = rms_to(relief, fused, &worst);
  std::printf("fused %zu points: rms distance to the design %.4f mm, max %.4f mm (noise 0.02 mm per axis)\n",
              fused.points.size(), rms, worst);
  for (size_t i = 1; i < 3; ++i)
    std::printf("view %zu: %s%s", i, report.checks[i].reason.c_str(),
                scan::format_pose_information(report.checks[i].information).c_str());
  EXPECT_LT(rms, 0.03);
  EXPECT_LT(worst, 0.15);
  // The corrections undo the nudges: 1 mm and 0.5 degree each.
  for (size_t i = 1; i < 3; ++i) EXPECT_NEAR(rotation_angle_deg(report.corrections[i]), 0.5, 0.05);
  // And bring each view to its true pose: the nudged pose corrected, against the truth, moves the relief's box
  // corners by at most 0.074 mm and turns it by 0.080 degree (a relief is a shallow surface, loosely held in tilt).
  for (size_t i = 1; i < 3; ++i) {
    const Eigen::Matrix4d error = report.corrections[i] * synthetic::nudge(1.0, 0.5, Vec3(1, -2, double(i)));
    EXPECT_LT(synthetic::box_corner_error(relief, error), 0.15) << "view " << i;
    EXPECT_LT(rotation_angle_deg(error), 0.15) << "view " << i;
  }
  // Without refinement the nudged views stand off the design.
  scan::FusionOptions trust;
  trust.refine = false;
  const double unrefined = rms_to(relief, scan::fuse_views(views, trust), &worst);
  EXPECT_GT(unrefined, 0.3);
}

TEST(ScanFuse, VoxelAndOutlierFiltersThin) {
  const Mesh relief = read_stl(std::string(ROSMILL_TEST_DATA) + "/mount_rush.stl");
  scan::FusionOptions o;
  o.voxel = 1.0;
  o.outlier_neighbours = 10;
  scan::FusionReport report;
  const PointCloud fused = scan::fuse_views(relief_views(relief), o, &report);
  EXPECT_LT(report.points_out, report.points_in / 2);
  double worst = 0;
  EXPECT_LT(rms_to(relief, fused, &worst), 0.1);
}

// Real data: the scan-N-plan workshop's part scan (a mesh from a robot cell's 3D camera, test/data) scanned again
// from two sides (a fifth of the second view's points lie on the first's), the second with its pose off by 1 mm and 0.5
// degree. The views fuse back onto the real surface, and the second view's pose comes back to its truth.
TEST(ScanFuse, TwoViewsOfARealPartScanFuseOntoItsSurface) {
  const Mesh part = read_ply_mesh(std::string(ROSMILL_TEST_DATA) + "/snp_part_scan.ply", 1000.0);  // metres
  const Vec3 centre = (part.bbox.min + part.bbox.max) / 2;
  const double reach = 2 * (part.bbox.max - part.bbox.min).norm();
  const Eigen::Matrix4d off = synthetic::nudge(1.0, 0.5, Vec3(1, 2, -1));
  std::vector<scan::ScanView> views;
  for (int i = 0; i < 2; ++i) {
    const Vec3 position = centre + reach * Vec3(i == 0 ? -1 : 1, 0.3, 1.5).normalized();
    const Eigen::Matrix4d pose = synthetic::sensor_pose(position, centre);
    scan::ScanView v;
    v.cloud.points = transformed_points(rigid_inverse(pose), synthetic::synthetic_scan(part, {position}, 30000, 0.02,
                                                                                      uint64_t(70 + i)).points);
    v.pose = i == 0 ? pose : Eigen::Matrix4d(off * pose);
    views.push_back(v);
  }
  scan::FusionReport report;
  const PointCloud fused = scan::fuse_views(views, {}, &report);
  double worst = 0;
  const double rms = rms_to(part, fused, &worst);
  const Eigen::Matrix4d error = report.corrections[1] * off;
  std::printf("snp_part_scan.ply, 2 views: %zu points fused, rms distance to the scan %.4f mm, max %.4f mm; second "
              "view %.4f mm and %.4f deg off its true pose (overlap %.2f)\n", fused.points.size(), rms, worst,
              synthetic::box_corner_error(part, error), rotation_angle_deg(error), report.overlaps[1]);
  EXPECT_LT(rms, 0.03);
  EXPECT_LT(synthetic::box_corner_error(part, error), 0.1);
  EXPECT_LT(rotation_angle_deg(error), 0.1);
  scan::FusionOptions trust;  // without refinement the nudged view stands off the surface
  trust.refine = false;
  EXPECT_GT(rms_to(part, scan::fuse_views(views, trust), &worst), 0.3);
}

TEST(ScanFuse, BadViewsAreRefusedWithTheReason) {
  EXPECT_NE(error_of([] { scan::fuse_views({}); }).find("no view"), std::string::npos);
  const Mesh relief = read_stl(std::string(ROSMILL_TEST_DATA) + "/mount_rush.stl");
  std::vector<scan::ScanView> views = relief_views(relief);
  auto with = [&](auto change) {
    std::vector<scan::ScanView> v = views;
    change(v);
    return error_of([&] { scan::fuse_views(v); });
  };
  EXPECT_NE(with([](auto& v) { v[1].pose(0, 3) = std::nan(""); }).find("view 2 (relief 1) pose"), std::string::npos);
  EXPECT_NE(with([](auto& v) { v[2].pose(0, 0) = 2; }).find("rigid"), std::string::npos);
  EXPECT_NE(with([](auto& v) { v[1].cloud.points.clear(); }).find("view 2 (relief 1): has 0 points"), std::string::npos);
  EXPECT_NE(with([](auto& v) { v[2].pose(2, 3) += 200; }).find("meets no other view"), std::string::npos);
}

TEST(ScanFuse, PoseFilesInBothForms) {
  const Eigen::Matrix4d m = scan::parse_pose("units: mm\nmatrix: [0, -1, 0, 10, 1, 0, 0, 20, 0, 0, 1, 30, 0, 0, 0, 1]",
                                            "a.yaml");
  EXPECT_NEAR(rotation_angle_deg(m), 90, 1e-9);
  EXPECT_NEAR(m(1, 3), 20, 1e-12);
  // A quarter turn about z, translation in metres (the default).
  const Eigen::Matrix4d q = scan::parse_pose("xyz: [0.01, 0.02, 0.03]\nquaternion: [0, 0, 0.7071067811865476, "
                                             "0.7071067811865476]", "b.yaml");
  EXPECT_TRUE(q.isApprox(m, 1e-9)) << q;
  const auto error = [](const std::string& text) { return error_of([&] { scan::parse_pose(text, "p.yaml"); }); };
  EXPECT_NE(error("xyz: [0, 0, 0]\nquaternion: [0, 0, 0, 2]").find("norm 1"), std::string::npos);
  EXPECT_NE(error("xyz: [.nan, 0, 0]\nquaternion: [0, 0, 0, 1]").find("NaN"), std::string::npos);
  EXPECT_NE(error("matrix: [1, 0, 0]").find("16 numbers"), std::string::npos);
  EXPECT_NE(error("matrix: [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]\nxyz: [0,0,0]").find("not both"), std::string::npos);
  EXPECT_NE(error("xyz: [0, 0, zero]\nquaternion: [0, 0, 0, 1]").find("not a number"), std::string::npos);
  EXPECT_NE(error("pose: 1").find("pose: unknown field (expected one of matrix, quaternion, units, xyz)"),
            std::string::npos);
}

namespace {

// Two views of `design` from `positions` (only faces within `incidence` degrees of the line to the sensor), the
// second with its pose off by `off`.
std::vector<scan::ScanView> two_views(const Mesh& design, const Vec3 (&positions)[2], double incidence,
                                      const Eigen::Matrix4d& off, uint64_t seed) {
  const Vec3 centre = (design.bbox.min + design.bbox.max) / 2;
  std::vector<scan::ScanView> views;
  for (int i = 0; i < 2; ++i) {
    const Eigen::Matrix4d pose = synthetic::sensor_pose(positions[i], centre);
    scan::ScanView v;
    v.cloud.points = transformed_points(rigid_inverse(pose), synthetic::synthetic_scan(design, {positions[i]}, 30000,
                                                                                      0.02, seed + uint64_t(i),
                                                                                      incidence).points);
    v.pose = i == 0 ? pose : Eigen::Matrix4d(off * pose);
    v.name = "view " + std::to_string(i);
    views.push_back(v);
  }
  return views;
}

}  // namespace

// Two views from above of a plate with engraved text (pycam-textbox; no return from its walls), the second's pose
// off by 1 mm and 0.5 degree in random directions: the overlap fixes z and the tilts, not x, y or the turn about
// z. The correction is marked ambiguous, naming the turn about z, never applied silently. And a correction beyond
// the stated pose error is withheld on the relief whose views fuse well: the view keeps its given pose.
TEST(ScanFuse, PlateViewsFromAboveAreMarkedAndLargeCorrectionsWithheld) {
  const Mesh plate = read_stl(std::string(ROSMILL_TEST_DATA) + "/pycam-textbox.stl");
  const Vec3 centre = (plate.bbox.min + plate.bbox.max) / 2;
  const Vec3 above[2] = {centre + Vec3(-20, 0, 400), centre + Vec3(20, 5, 400)};
  std::mt19937_64 rng(5);
  std::normal_distribution<double> gauss;
  const int trials = rosmill::testing::cases(4, 1);
  int wrong_and_certain = 0;
  for (int t = 0; t < trials; ++t) {
    const Vec3 axis(gauss(rng), gauss(rng), gauss(rng));
    const Eigen::Matrix4d off = synthetic::nudge(1.0, 0.5, axis);
    const std::vector<scan::ScanView> views = two_views(plate, above, 60, off, 90 + uint64_t(10 * t));
    scan::FusionReport report;
    const PointCloud fused = scan::fuse_views(views, {}, &report);
    const scan::ViewCorrection& c = report.checks[1];
    double worst = 0;
    const double rms = rms_to(plate, fused, &worst);
    std::printf("plate from above, trial %d: correction %.3f mm %.3f deg, %s%s (%s)\n", t, c.moved_mm, c.turned_deg,
                c.applied ? "applied" : "withheld", c.locked ? ", weak directions locked" : "", c.reason.c_str());
    EXPECT_TRUE(c.ambiguous);
    EXPECT_TRUE(c.locked);
    EXPECT_EQ(report.ambiguous, 1u);
    EXPECT_NE(c.reason.find("rotation about the reference's z axis"), std::string::npos) << c.reason;
    // The pose the view ends with against the truth (off^-1), along each direction: a direction not named weak
    // is within 3 stated sigmas.
    const std::array<double, 6> e = synthetic::error_by_dof(c.information, report.corrections[1] * off);
    wrong_and_certain += wrong_and_certain_directions(c.information, e);
    std::printf("; fused rms %.3f mm, max %.3f mm\n", rms, worst);
  }
  EXPECT_EQ(wrong_and_certain, 0);
  // A relief whose views fuse well: a stated pose error below the real one withholds the corrections.
  const Mesh relief = read_stl(std::string(ROSMILL_TEST_DATA) + "/mount_rush.stl");
  scan::FusionOptions strict;
  // The views are off by 0.5 degree (about the common origin: millimetres at the views): stated errors far below
  // that withhold every correction, however the correction splits into turn and shift.
  strict.pose_error_deg = 0.05;
  strict.pose_error_mm = 0.1;
  scan::FusionReport report;
  scan::fuse_views(relief_views(relief), strict, &report);
  for (size_t i = 1; i < 3; ++i) {
    EXPECT_FALSE(report.checks[i].applied) << i;
    EXPECT_TRUE(report.checks[i].exceeds_pose_error) << i;
    EXPECT_TRUE(report.corrections[i].isIdentity(1e-12));
    EXPECT_NE(report.checks[i].reason.find("exceeds the stated pose error"), std::string::npos);
  }
}

// Two views of a turned part from its side (the test cylinder, r 25 h 60, 36 facets; caps unseen), 30 degrees
// apart, the second's pose off by 1 mm and 0.5 degree in random directions: the overlap leaves the slide along the
// axis to the mantle's ends alone, and that slide is named weak. The ICP rolls the view about the axis until the
// two seen patches coincide (about 30 degrees: the pairs at the reference's border drag it), a correction beyond
// the stated pose error, so it is withheld: the view keeps its given pose. A correction applied (weak motions
// locked) has no direction stated certain off by more than 3 sigma; a withheld one is not counted (the view keeps
// its given pose, as uncertain as the stated pose error).
TEST(ScanFuse, CylinderViewsFromTheSideNameTheirAxisAndApplyNothingSilently) {
  const Mesh cylinder = build_mesh(cylinder_corners());
  const Vec3 centre = (cylinder.bbox.min + cylinder.bbox.max) / 2;
  const Vec3 side[2] = {centre + 400 * Vec3(std::cos(0.26), std::sin(0.26), 0),
                        centre + 400 * Vec3(std::cos(-0.26), std::sin(-0.26), 0)};
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss;
  const int trials = rosmill::testing::cases(4, 1);
  int wrong_and_certain = 0;
  for (int t = 0; t < trials; ++t) {
    const Eigen::Matrix4d off = synthetic::nudge(1.0, 0.5, Vec3(gauss(rng), gauss(rng), gauss(rng)));
    scan::FusionReport report;
    const PointCloud fused = scan::fuse_views(two_views(cylinder, side, 80, off, 40 + uint64_t(10 * t)), {}, &report);
    const scan::ViewCorrection& c = report.checks[1];
    double worst = 0;
    const double rms = rms_to(cylinder, fused, &worst);
    std::printf("cylinder from the side, trial %d: %s\n", t, c.reason.c_str());
    // The sigmas follow the residuals now (pose_information.hpp), no longer a cap on how many points count: the
    // 36 facets' 10-degree kinks hold the roll, and at the roll by three facets where the ICP lands the pairs fit
    // well and fix every direction. That correction exceeds the stated pose error and is withheld, so nothing is
    // applied silently; only a correction that is applied must name the axis weak and lock it.
    EXPECT_TRUE(c.ambiguous || !c.applied);
    EXPECT_TRUE(c.locked || !c.applied);
    if (!c.applied) {
      EXPECT_TRUE(report.corrections[1].isIdentity(1e-12));
    } else {
      EXPECT_NE(c.reason.find("translation along the reference's z axis"), std::string::npos) << c.reason;
    }
    const std::array<double, 6> e = synthetic::error_by_dof(c.information, report.corrections[1] * off);
    const size_t wrong = wrong_and_certain_directions(c.information, e);
    if (c.applied) wrong_and_certain += wrong;
    for (const scan::PoseDirection& d : c.information.dofs)
      if (c.applied && !d.rotation && std::abs(d.axis.z()) > 0.99) {
        EXPECT_TRUE(d.weak) << d.name;  // the slide along the axis (z)
      }
    std::printf("; fused rms %.3f mm, max %.3f mm\n", rms, worst);
  }
  EXPECT_EQ(wrong_and_certain, 0);
}
