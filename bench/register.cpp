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
//   calibration  the stated uncertainty against the true error: registration of single scans (featuretype and
//             the counter from above and two sides, mount_rush from above, a plate from above, a cylinder from its
//             side) and fusion of views (three of mount_rush and of the counter from around them, two of the plate
//             from above and of the cylinder from its side, the further views nudged by 1 mm / 0.5 degree about a
//             random axis), in random poses (fixed seeds). Per part and degree of freedom (the report's principal
//             frame): the trials, the RMS true error, the median stated 1 sigma, their ratio, the trials beyond
//             3 sigma (a free direction makes no claim) and those called weak.
// Usage: bench_register [threads] [pcl_poses] [fuse]   (pcl_poses: how many of the 5 poses pcl_icp also runs,
//        default 5; it takes 1-2 minutes per pose on 2 cores. `fuse`: the fusion figures only)
//        bench_register calibration [trials] [threads] [only]   (trials per part, default 20; only: the parts
//             whose name holds it, "fuse " before a fusion's: "fuse counter", "register plate"... "counter")
#include <algorithm>
#include <array>
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
#include "rosmill/error.hpp"
#include "rosmill/heap_reuse.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/scan/design_registration.hpp"
#include "rosmill/scan/mesh_distance.hpp"
#include "rosmill/scan/surface_sample.hpp"
#include "rosmill/scan/thinning.hpp"
#include "rosmill/scan/view_fusion.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/testing/pose_error.hpp"
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


// The true errors and stated sigmas of one part's trials, per degree of freedom.
struct Calibration {
  std::string name;
  std::array<std::vector<double>, 6> error, sigma;  // |error| and sigma per trial (mm, degrees)
  std::array<int, 6> beyond{}, weak{}, free{};
  int refused = 0, ambiguous = 0, trials = 0;
  void add(const scan::PoseInformation& info, const Eigen::Matrix4d& error_motion) {
    const std::array<double, 6> e = synthetic::error_by_dof(info, error_motion);
    ++trials;
    ambiguous += info.ambiguous();
    for (size_t k = 0; k < 6; ++k) {
      const scan::PoseDirection& d = info.dofs[k];
      weak[k] += d.weak;
      if (d.free) {
        ++free[k];
        continue;
      }
      error[k].push_back(std::abs(e[k]));
      sigma[k].push_back(d.sigma);
      beyond[k] += std::abs(e[k]) > 3 * d.sigma;
    }
  }
  void print() const {
    static const char* const kDof[6] = {"slide 1", "slide 2", "slide 3", "turn 1", "turn 2", "turn 3"};
    std::printf("%s: %d trials (%d refused, %d ambiguous)\n", name.c_str(), trials, refused, ambiguous);
    for (size_t k = 0; k < 6; ++k) {
      double sum = 0;
      for (double x : error[k]) sum += x * x;
      const double rms = error[k].empty() ? 0 : std::sqrt(sum / double(error[k].size()));
      std::vector<double> s = sigma[k];
      double median = 0;
      if (!s.empty()) {
        std::nth_element(s.begin(), s.begin() + long(s.size() / 2), s.end());
        median = s[s.size() / 2];
      }
      const char* unit = k < 3 ? "mm" : "deg";
      std::printf("  %-7s: %3zu trials, rms error %.5f %s, median sigma %.5f %s, ratio %6.2f, beyond 3 sigma %d, "
                  "weak %d, free %d\n", kDof[k], error[k].size(), rms, unit, median, unit,
                  rms > 0 ? median / rms : 0.0, beyond[k], weak[k], free[k]);
    }
  }
};

struct CalibrationPart {
  std::string name;
  Mesh design;
  std::vector<Vec3> sensors;  // registration: one scan seen by all; fusion: a view each
  double incidence = 90;
  std::vector<Eigen::Matrix4d> symmetries;  // the error is taken against the nearest symmetric pose
};

// The design-frame error motion against the nearest of the symmetric poses.
Eigen::Matrix4d nearest_error(const Eigen::Matrix4d& truth, const Eigen::Matrix4d& found,
                              const std::vector<Eigen::Matrix4d>& symmetries) {
  Eigen::Matrix4d error = rigid_inverse(truth) * found;
  for (const Eigen::Matrix4d& s : symmetries)
    if (rotation_angle_deg(rigid_inverse(truth) * found * s) < rotation_angle_deg(error))
      error = rigid_inverse(truth) * found * s;
  return error;
}

Calibration calibrate_registration(const CalibrationPart& part, int trials, size_t samples, uint64_t seed) {
  Calibration c;
  c.name = "register " + part.name;
  std::mt19937_64 rng(seed);
  for (int i = 0; i < trials; ++i) {
    const PointCloud seen = synthetic::synthetic_scan(part.design, part.sensors, samples, 0.02, seed + uint64_t(i),
                                                      part.incidence);
    const Eigen::Matrix4d truth = synthetic::random_rigid(rng, 200);
    PointCloud scan;
    scan.points = transformed_points(truth, seen.points);
    scan.recompute_bbox();
    try {
      const scan::RegistrationResult r = scan::register_design(part.design, scan);
      c.add(r.information, nearest_error(truth, r.transform, part.symmetries));
      if (i == 0 && std::getenv("CALIBRATION_DETAIL")) std::printf("%s", scan::format_pose_information(r.information).c_str());
    } catch (const Error&) {
      ++c.refused;
    }
  }
  return c;
}

// Views of the part from its sensors, each in its sensor's frame, the first at its true pose, the others nudged;
// each further view's final pose against its truth, in the common frame, beside its last refinement's sigmas.
Calibration calibrate_fusion(const CalibrationPart& part, int trials, size_t samples, uint64_t seed, double* worst_rms) {
  Calibration c;
  c.name = "fuse " + part.name;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  const Vec3 centre = (part.design.bbox.min + part.design.bbox.max) / 2;
  const scan::MeshDistance distance(part.design);
  *worst_rms = 0;
  for (int t = 0; t < trials; ++t) {
    std::vector<scan::ScanView> views;
    std::vector<Eigen::Matrix4d> truths;
    for (size_t i = 0; i < part.sensors.size(); ++i) {
      const Eigen::Matrix4d pose = synthetic::sensor_pose(part.sensors[i], centre);
      scan::ScanView v;
      v.cloud.points = transformed_points(rigid_inverse(pose),
                                          synthetic::synthetic_scan(part.design, {part.sensors[i]}, samples, 0.02,
                                                                    seed + uint64_t(100 * t) + i, part.incidence).points);
      const Vec3 axis(gauss(rng), gauss(rng), gauss(rng));
      v.pose = i == 0 ? pose : Eigen::Matrix4d(synthetic::nudge(1.0, 0.5, axis) * pose);
      truths.push_back(pose);
      views.push_back(std::move(v));
    }
    scan::FusionReport report;
    const PointCloud fused = scan::fuse_views(views, {}, &report);
    const std::vector<double> d = distance.distances(fused.points);
    double sum = 0;
    for (double x : d) sum += x * x;
    *worst_rms = std::max(*worst_rms, std::sqrt(sum / double(d.size())));
    for (size_t i = 1; i < views.size(); ++i) {
      // The found pose against the truth: a motion of the common frame.
      const Eigen::Matrix4d error = report.corrections[i] * views[i].pose * rigid_inverse(truths[i]);
      if (!report.checks[i].applied) ++c.refused;
      c.add(report.checks[i].information, error);
      if (t == 0 && std::getenv("CALIBRATION_DETAIL"))
        std::printf("%s", scan::format_pose_information(report.checks[i].information).c_str());
    }
  }
  return c;
}

// A cylinder r 25 h 60 about z with `facets` facets, and its symmetries (a facet's turn, turned end for end).
Mesh faceted_cylinder(int facets, std::vector<Eigen::Matrix4d>* symmetries) {
  std::vector<Vec3> corners;
  const auto at = [&](int k, double z) {
    return Vec3(25 * std::cos(2 * M_PI * k / facets), 25 * std::sin(2 * M_PI * k / facets), z);
  };
  for (int k = 0; k < facets; ++k)
    for (const Vec3& p : {at(k, 0), at(k + 1, 0), at(k + 1, 60), at(k, 0), at(k + 1, 60), at(k, 60), Vec3(0, 0, 60),
                          at(k, 60), at(k + 1, 60), Vec3(0, 0, 0), at(k + 1, 0), at(k, 0)})
      corners.push_back(p);
  for (int k = 0; k < facets; ++k)
    for (int over = 0; over < 2; ++over) {
      Eigen::Matrix4d s = Eigen::Matrix4d::Identity();
      s.topLeftCorner<3, 3>() = Eigen::AngleAxisd(2 * M_PI * k / facets, Vec3::UnitZ()).toRotationMatrix() *
                                Eigen::AngleAxisd(over * M_PI, Vec3::UnitX()).toRotationMatrix();
      s(2, 3) = over ? 60 : 0;
      symmetries->push_back(s);
    }
  return build_mesh(corners);
}

std::vector<Vec3> around(const Mesh& design, int count, double distance, double elevation) {
  const Vec3 centre = (design.bbox.min + design.bbox.max) / 2;
  std::vector<Vec3> out;
  for (int i = 0; i < count; ++i) {
    const double a = 2 * M_PI * i / count;
    out.push_back(centre + distance * Vec3(std::cos(a), std::sin(a), elevation).normalized());
  }
  return out;
}

int calibration(int trials, const std::string& only) {
  const std::string stl = std::string(ROSMILL_SHARED_DATA) + "/stl/";
  StlReadOptions inch;
  inch.units = Units::Inch;
  const Mesh featuretype = read_stl(stl + "featuretype.STL", inch);
  const Mesh counter = read_stl(stl + "counter.unitsmm.STL");
  const Mesh mount_rush = read_stl(stl + "mount_rush.stl");
  const Mesh plate = read_stl(stl + "pycam-textbox.stl");
  std::vector<Eigen::Matrix4d> symmetries;
  const Mesh cylinder = faceted_cylinder(360, &symmetries);
  const Vec3 plate_centre = (plate.bbox.min + plate.bbox.max) / 2;
  const Vec3 cylinder_centre = (cylinder.bbox.min + cylinder.bbox.max) / 2;
  const std::vector<CalibrationPart> registrations{
      {"featuretype, above and two sides", featuretype, synthetic::sensors_above(featuretype, 2, 1000), 90, {}},
      {"counter, above and two sides", counter, synthetic::sensors_above(counter, 2, 1000), 90, {}},
      {"mount_rush, above", mount_rush, synthetic::sensors_above(mount_rush, 0, 1000), 90, {}},
      {"plate (pycam-textbox), above", plate, synthetic::sensors_above(plate, 0, 1000), 60, {}},
      {"cylinder, side", cylinder, {Vec3(1000, 0, 30)}, 80, symmetries}};
  const std::vector<CalibrationPart> fusions{
      {"mount_rush, 3 views around", mount_rush, around(mount_rush, 3, 400, 1.5), 90, {}},
      {"counter, 3 views around", counter, around(counter, 3, 400, 1.5), 90, {}},
      {"plate (pycam-textbox), 2 views above", plate,
       {plate_centre + Vec3(-20, 0, 400), plate_centre + Vec3(20, 5, 400)}, 60, {}},
      {"cylinder, 2 views side", cylinder,
       {cylinder_centre + 400 * Vec3(std::cos(0.26), std::sin(0.26), 0),
        cylinder_centre + 400 * Vec3(std::cos(-0.26), std::sin(-0.26), 0)}, 80, {}}};
  uint64_t seed = 500;
  for (const CalibrationPart& p : registrations) {
    seed += 1000;  // the same seeds whichever parts run
    if (("register " + p.name).find(only) == std::string::npos) continue;
    const auto t0 = std::chrono::steady_clock::now();
    calibrate_registration(p, trials, 30000, seed).print();
    std::printf("  (%.1f s)\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  for (const CalibrationPart& p : fusions) {
    seed += 1000;
    if (("fuse " + p.name).find(only) == std::string::npos) continue;
    const auto t0 = std::chrono::steady_clock::now();
    double worst_rms = 0;
    const Calibration c = calibrate_fusion(p, trials, 100000, seed, &worst_rms);
    c.print();
    std::printf("  (withheld counted as refused; worst fused RMS to the design %.4f mm; %.1f s)\n", worst_rms,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  rosmill::core::keep_freed_memory();  // repeated jobs reuse their memory (see heap_reuse.hpp)
  if (argc > 1 && std::string(argv[1]) == "calibration") {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              size_t(std::max(1, argc > 3 ? std::atoi(argv[3]) : 2)));
    return calibration(argc > 2 ? std::atoi(argv[2]) : 20, argc > 4 ? argv[4] : "");
  }
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
