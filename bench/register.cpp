// Registration and fusion at the sizes of a cell's scans, with accuracy against known transforms:
//   register  demo2.stl.gz (146,336 triangles, ../shared/data/stl) scanned synthetically (a view from above and
//             two at 45 degrees, 0.02 mm noise), ~300k points, in 5 random poses (fixed seeds); no initial guess.
//             Prints per pose the global and fine seconds and the errors (the largest displacement of the design's
//             box corners, and the rotation angle of truth^-1 * found).
//   fuse      5 views x 300k points of the same part with poses nudged by 1 mm / 0.5 degree, fused with ICP
//             refinement (2 rounds) and a 0.2 mm voxel grid.
//   fpfh      the peer of the global step, per pose: PCL's FPFH features and SampleConsensusPrerejective (its
//             tutorial's robust pose estimation, fpfh_global.hpp) on the scan thinned to registration's voxel,
//             normals oriented towards the sensor above; its time and errors beside ours (global step only).
//   pcl_icp   when PCL's own tool is on PATH (Debian pcl-tools; bench/run installs it): the same scans written as
//             PCD (the scan as source, 300k design surface samples as target) and given to `pcl_icp` after an
//             initial alignment by the true pose nudged by 1 mm and 1 degree (pcl_icp has no global step); its
//             final transform is read from its output and its errors printed beside ours.
// Usage: bench_register [threads] [pcl_poses] [fuse]   (pcl_poses: how many of the 5 poses pcl_icp also runs,
//        default 5; it takes 1-2 minutes per pose on 2 cores. `fuse`: the fusion figures only)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>

#include <Eigen/Geometry>
#include <tbb/global_control.h>
#include <unistd.h>

#include "cpu_time.hpp"
#include "fpfh_global.hpp"
#include "rosmill/heap_reuse.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/scan/design_registration.hpp"
#include "rosmill/scan/surface_sample.hpp"
#include "rosmill/scan/thinning.hpp"
#include "rosmill/scan/view_fusion.hpp"
#include "rosmill/testing/synthetic_scan.hpp"

using namespace rosmill::core;

namespace {

// pcl_icp's last 4x4 matrix in its output (rows of 4 numbers), or NaN when there is none.
Eigen::Matrix4d last_matrix(const std::string& text) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream l(line);
    std::vector<double> v;
    double x;
    while (l >> x) v.push_back(x);
    if (v.size() == 4 && l.eof()) rows.push_back(v);
  }
  Eigen::Matrix4d m = Eigen::Matrix4d::Constant(std::nan(""));
  if (rows.size() < 4) return m;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) m(i, k) = rows[rows.size() - 4 + size_t(i)][size_t(k)];
  return m;
}

std::string run(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return out;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  ::pclose(pipe);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  rosmill::core::keep_freed_memory();  // repeated jobs reuse their memory (see heap_reuse.hpp)
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  const int pcl_poses = argc > 2 ? std::atoi(argv[2]) : 5;
  const bool fuse_only = argc > 3 && std::string(argv[3]) == "fuse";
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(std::max(1, threads)));
  const Mesh design = read_stl(std::string(ROSMILL_SHARED_DATA) + "/stl/demo2.stl.gz");
  std::printf("design demo2.stl.gz: %zu triangles, %d threads\n", design.face_count(), threads);
  const auto sensors = synthetic::sensors_above(design, 2, 1000);
  const bool have_pcl_icp = pcl_poses > 0 && !run("command -v pcl_icp").empty();
  const std::string dir = std::filesystem::temp_directory_path() / ("rosmill_bench_register_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  if (have_pcl_icp) {
    PointCloud target;
    target.points = scan::sample_surface(design, 300000, 7).points;
    write_cloud(dir + "/design.pcd", target, Units::Millimetre);
  }
  // The feature peer's design: 20k area-weighted samples with their faces' normals; registration's voxel.
  const scan::SurfaceSample feature_design = scan::sample_surface(design, 20000, 11);
  double area = 0;
  for (double a : design.areas) area += a;
  const double leaf = std::sqrt(area / 3000);
  std::mt19937_64 rng(2026);
  double worst_t = 0, worst_r = 0, worst_seconds = 0;
  for (int pose = 0; pose < (fuse_only ? 0 : 5); ++pose) {
    const Eigen::Matrix4d truth = synthetic::random_rigid(rng, 200);
    PointCloud scan;
    scan.points = transformed_points(truth, synthetic::synthetic_scan(design, sensors, 420000, 0.02, 100 + pose).points);
    const double c0 = cpu_seconds_used();
    const auto t0 = std::chrono::steady_clock::now();
    const scan::RegistrationResult r = scan::register_design(design, scan);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const Eigen::Matrix4d error = rigid_inverse(truth) * r.transform;
    worst_t = std::max(worst_t, synthetic::box_corner_error(design, error));
    worst_r = std::max(worst_r, rotation_angle_deg(error));
    worst_seconds = std::max(worst_seconds, wall);
    std::printf("register pose %d: %zu points, %.3f s wall (global %.3f, fine %.3f; %.3f s CPU), rms %.4f mm, "
                "inliers %.4f, error %.5f mm %.5f deg\n",
                pose, scan.points.size(), wall, r.global_seconds, r.fine_seconds, cpu_seconds_used() - c0, r.rms,
                r.inlier_share, synthetic::box_corner_error(design, error), rotation_angle_deg(error));
    std::printf("  %zu candidates; phases: %s\n", r.candidates, scan::format_phases(r.phases).c_str());
    const Vec3 viewpoint = (truth * sensors.front().homogeneous()).head<3>();
    const rosmill::bench::FpfhGlobal f = rosmill::bench::fpfh_global(scan::thin_by_voxel(scan.points, leaf), viewpoint,
                                                   feature_design.points, feature_design.normals, leaf);
    const Eigen::Matrix4d f_error = rigid_inverse(truth) * f.design_to_scan;
    std::printf("  PCL FPFH + SampleConsensusPrerejective (global step only, %.2f mm voxel): %.3f s wall, %s, "
                "inliers %.3f, error %.3f mm %.3f deg (rosmill's global step %.3f s, then fine)\n",
                leaf, f.seconds, f.converged ? "converged" : "not converged", f.inlier_share,
                synthetic::box_corner_error(design, f_error), rotation_angle_deg(f_error), r.global_seconds);
    if (!have_pcl_icp || pose >= pcl_poses) continue;
    // pcl_icp moves the source (the scan) onto the target (the design): it starts from the scan brought back by
    // a nudged inverse of the truth.
    const Eigen::Matrix4d start = synthetic::nudge(1.0, 1.0, Vec3(1, 2, 3)) * rigid_inverse(truth);
    PointCloud moved;
    moved.points = transformed_points(start, scan.points);
    write_cloud(dir + "/scan.pcd", moved, Units::Millimetre);
    const auto p0 = std::chrono::steady_clock::now();
    // pcl_icp's options: -d the pairing distance, -i the iterations (-n is its switch to Levenberg-Marquardt).
    const std::string out = run("cd " + dir + " && pcl_icp design.pcd scan.pcd -d 5 -i 100 2>&1");
    const double pcl_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - p0).count();
    const Eigen::Matrix4d step = last_matrix(out);
    // pcl_icp's transform maps the (pre-moved) scan onto the design: the design -> scan pose is its inverse.
    const Eigen::Matrix4d found = rigid_inverse(step * start);
    const Eigen::Matrix4d pcl_error = rigid_inverse(truth) * found;
    std::printf("  pcl_icp (start: truth nudged 1 mm, 1 deg; -d 5 -i 100): %.3f s wall, error %.5f mm %.5f deg\n",
                pcl_wall, step.allFinite() ? synthetic::box_corner_error(design, pcl_error) : std::nan(""),
                step.allFinite() ? rotation_angle_deg(pcl_error) : std::nan(""));
  }
  if (!fuse_only) std::printf("register: worst %.3f s, max error %.5f mm, %.5f deg\n", worst_seconds, worst_t, worst_r);

  // Fusion: 5 views, each ~300k points in its sensor's frame, poses nudged.
  std::vector<scan::ScanView> views;
  std::vector<Eigen::Matrix4d> true_poses;
  const Vec3 centre = (design.bbox.min + design.bbox.max) / 2;
  for (int i = 0; i < 5; ++i) {
    const double a = 2 * M_PI * i / 5;
    const Vec3 position = centre + 600 * Vec3(std::cos(a), std::sin(a), 2).normalized();
    Eigen::Matrix4d pose = Eigen::Matrix4d::Identity();
    pose.topRightCorner<3, 1>() = position;
    scan::ScanView v;
    v.cloud.points = transformed_points(rigid_inverse(pose),
                                        synthetic::synthetic_scan(design, {position}, 330000, 0.02, 50 + i).points);
    v.pose = i == 0 ? pose : Eigen::Matrix4d(synthetic::nudge(1.0, 0.5, Vec3(1, -2, i)) * pose);
    true_poses.push_back(pose);
    views.push_back(std::move(v));
  }
  scan::FusionOptions o;
  o.voxel = 0.2;
  scan::FusionReport report;
  const double c0 = cpu_seconds_used();
  scan::fuse_views(views, o, &report);
  // Each view's refined pose against its true pose (the first view is the reference and was not nudged).
  double worst_mm = 0, worst_deg = 0;
  for (size_t i = 1; i < views.size(); ++i) {
    const Eigen::Matrix4d error = report.corrections[i] * views[i].pose * rigid_inverse(true_poses[i]);  // common frame
    worst_mm = std::max(worst_mm, synthetic::box_corner_error(design, error));
    worst_deg = std::max(worst_deg, rotation_angle_deg(error));
  }
  std::printf("fuse: 5 views, %zu points in, %zu out, %.3f s wall (%.3f s CPU); views 2-5 off their true poses by "
              "at most %.4f mm (design box corners) and %.4f deg after the 1 mm / 0.5 deg nudges\n",
              report.points_in, report.points_out, report.seconds, cpu_seconds_used() - c0, worst_mm, worst_deg);
  std::printf("  phases: %s\n", scan::format_phases(report.phases).c_str());
  std::filesystem::remove_all(dir);
  return 0;
}
