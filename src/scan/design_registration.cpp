#include "rosmill/scan/design_registration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>

#include <Eigen/Geometry>
#include <Eigen/QR>

#include "rosmill/error.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/number_text.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/scan/covered_share.hpp"
#include "rosmill/scan/design_symmetry.hpp"
#include "rosmill/scan/mesh_distance.hpp"
#include "rosmill/scan/near_surface_cells.hpp"
#include "rosmill/scan/plane_icp.hpp"
#include "rosmill/scan/principal_axes.hpp"
#include "rosmill/scan/surface_normals.hpp"
#include "rosmill/scan/surface_sample.hpp"
#include "rosmill/scan/thinning.hpp"
#include "rosmill/seconds_since.hpp"

namespace rosmill::core::scan {
namespace {

const char* const kWhere = "registration";

struct Fit {
  Eigen::Matrix4d scan_to_design = Eigen::Matrix4d::Identity();
  double share = 0, rms = 0;
};

// The fit of the scan points brought into the design's frame, from their exact distances to its triangles; only
// the inliers' distances are sought exactly (a point beyond `inlier_distance` costs a short descent of the tree).
// `nearest` receives each point's nearest surface point, with face kNone for an outlier.
Fit measure(const MeshDistance& design, const std::vector<Vec3>& in_design, const Eigen::Matrix4d& scan_to_design,
            double inlier_distance, std::vector<SurfaceDistance>& nearest) {
  Fit fit;
  fit.scan_to_design = scan_to_design;
  SurfaceDistance outlier;
  outlier.face = kNone;
  nearest.assign(in_design.size(), outlier);
  for_each_piece<size_t>(0, in_design.size(), 256, [&](size_t begin, size_t end) {
    for (size_t i = begin; i != end; ++i)
      if (!design.query_within(in_design[i], inlier_distance, nearest[i])) nearest[i].face = kNone;
  });
  double sum_sq = 0;
  size_t inliers = 0;
  for (const SurfaceDistance& s : nearest)
    if (s.face != kNone) {
      sum_sq += s.signed_distance * s.signed_distance;
      ++inliers;
    }
  fit.share = nearest.empty() ? 0 : double(inliers) / double(nearest.size());
  fit.rms = inliers ? std::sqrt(sum_sq / double(inliers)) : std::numeric_limits<double>::infinity();
  return fit;
}

Fit measure(const MeshDistance& design, const std::vector<Vec3>& scan, const Eigen::Matrix4d& scan_to_design,
            double inlier_distance) {
  std::vector<SurfaceDistance> unused;
  return measure(design, transformed_points(scan_to_design, scan), scan_to_design, inlier_distance, unused);
}

bool better(const Fit& a, const Fit& b) { return a.share > b.share + 1e-9 || (a.share >= b.share - 1e-9 && a.rms < b.rms); }

// Poses that differ by less than `degrees` and `length` mm.
bool same_pose(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b, double length, double degrees = 2.0) {
  const Eigen::Matrix4d d = rigid_inverse(a) * b;
  return rotation_angle_deg(d) < degrees && translation_length(d) < length;
}

// The global step's candidates pulled in by coarse ICP, first with a reach of a fifth of the part (to pull them in
// from the principal-axes guess) then of 3 voxels (to settle), at most 25 steps each. They run as a race (Maron &
// Moore, "Hoeffding races: accelerating model selection search", 1994): in rounds of 5 steps, the candidates of a
// round side by side; after each round every candidate's share of points near the design is scored (on the cells
// near its surface, a lookup a point) and those that trail the best so far by more than a quarter of the scan drop
// out (a wrong principal-axes guess fits half the scan or less and gains little from more steps, while the right
// one fits nearly all of it within a few). Candidates that fit about equally, a symmetric part's, all run to the
// end. `incumbent`: the share of a fit found before, which the candidates trail from the first round on. Returns
// every candidate's last fit, measured exactly.
std::vector<Fit> race_candidates(const PlaneIcp& icp, const NearSurfaceCells& cells, const MeshDistance& distance,
                                 const std::vector<Vec3>& coarse, const std::vector<Eigen::Matrix4d>& candidates,
                                 double size, double leaf, double incumbent = 0) {
  constexpr int kRound = 5, kStageSteps = 25;
  constexpr double kTrail = 0.25;
  const double reach[2] = {0.2 * size, 3 * leaf};
  // The long-reach pull-in moves a candidate by up to a fifth of the part: a quarter of the points steer it as well.
  const std::vector<Vec3> pull_in = thin_evenly(coarse, std::max<size_t>(coarse.size() / 4, 50));
  struct Runner {
    Eigen::Matrix4d pose;
    int stage = 0, steps = 0;
    bool running = true;
    double share = 0;  // near the design, scored on its cells
  };
  std::vector<Runner> runners;
  for (const Eigen::Matrix4d& c : candidates) {
    runners.emplace_back();
    runners.back().pose = rigid_inverse(c);
  }
  for (;;) {
    std::vector<size_t> running;
    for (size_t i = 0; i < runners.size(); ++i)
      if (runners[i].running) running.push_back(i);
    if (running.empty()) break;
    for_each_index(size_t(0), running.size(), [&](size_t k) {
      Runner& c = runners[running[k]];
      IcpOutcome outcome;
      const int steps = std::min(kRound, kStageSteps - c.steps);
      c.pose = icp.align(c.stage == 0 ? pull_in : coarse, c.pose, reach[c.stage], steps, &outcome);
      c.steps += outcome.steps;
      if (outcome.converged || outcome.pairs < 6 || c.steps >= kStageSteps) {
        c.steps = 0;
        c.running = ++c.stage < 2;
      }
      c.share = cells.share_near(coarse, c.pose);
    });
    double best = incumbent;
    for (const Runner& c : runners) best = std::max(best, c.share);
    for (Runner& c : runners)
      if (c.share < best - kTrail) c.running = false;
  }
  std::vector<Fit> fits(runners.size());
  for_each_index(size_t(0), runners.size(),
                 [&](size_t i) { fits[i] = measure(distance, coarse, runners[i].pose, leaf); });
  return fits;
}

std::string vector_text(const Vec3& a) {
  return "(" + decimal_text(a.x(), 3) + ", " + decimal_text(a.y(), 3) + ", " + decimal_text(a.z(), 3) + ")";
}

// "a 180.0 deg turn about (0.000, 1.000, 0.000)": a rigid motion in words.
std::string describe_motion(const Eigen::Matrix4d& m) {
  const Eigen::AngleAxisd turn(Eigen::Matrix3d(m.topLeftCorner<3, 3>()));
  const Vec3& a = turn.axis();
  return "a " + decimal_text(turn.angle() * 180 / M_PI, 1) + " deg turn about " + vector_text(a);
}

SymmetryOptions symmetry_options(const RegistrationOptions& o) {
  SymmetryOptions s;
  s.moment_tolerance = o.moment_tolerance;
  s.inlier_distance = o.inlier_distance;
  s.min_share = 1 - o.ambiguity_share;
  s.tolerance = 0.1 * o.inlier_distance;
  return s;
}

}  // namespace

void RegistrationOptions::check() const {
  const auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw Error(std::string("registration option ") + name, "must be a positive number");
  };
  positive(inlier_distance, "inlier_distance");
  positive(max_rms, "max_rms");
  positive(moment_tolerance, "moment_tolerance");
  positive(ambiguity_share, "ambiguity_share");
  if (!(ambiguity_rms >= 1) || !std::isfinite(ambiguity_rms))
    throw Error("registration option ambiguity_rms", "must be a factor >= 1");
  for (auto [v, name] : {std::pair{min_inlier_share, "min_inlier_share"}, {min_overlap, "min_overlap"}})
    if (!(v >= 0 && v <= 1)) throw Error(std::string("registration option ") + name, "must lie in [0, 1]");
  information.check();
  if (design_points < 100 || coarse_points < 50 || fine_points < 50)
    throw Error("registration options", "design_points >= 100, coarse_points >= 50 and fine_points >= 50 are needed");
}

RegistrationResult register_design(const Mesh& design, const PointCloud& scan, const RegistrationOptions& o) {
  o.check();
  check_has_area(design, "registration: the design");
  if (scan.points.size() < 50) throw Error(kWhere, "the scan has " + std::to_string(scan.points.size()) +
                                                       " points; at least 50 are needed");
  const auto start = std::chrono::steady_clock::now();
  RegistrationResult r;
  PhaseClock clock(r.phases);
  const SurfaceSample target = sample_surface(design, o.design_points, o.seed);
  const double area = std::accumulate(design.areas.begin(), design.areas.end(), 0.0);
  const double size = design.bbox.size().norm();
  const PrincipalFrame design_frame = principal_frame(target.points);
  const Vec3 centre = design_frame.centroid;
  clock.lap("design sampling");
  const MeshDistance distance(design);
  clock.lap("triangle index");
  const PlaneIcp icp(target.points, target.normals);
  clock.lap("ICP index");
  const std::vector<Eigen::Matrix4d> symmetries =
      design_symmetries(design, target, design_frame, icp, distance, symmetry_options(o));
  clock.lap("design symmetries");

  // Global: every principal-axes candidate pulled in by coarse ICP.
  const double leaf = std::sqrt(area / double(o.coarse_points));
  const std::vector<Vec3> coarse = thin_by_voxel(scan.points, leaf);
  if (coarse.size() < 10) throw Error(kWhere, "the scan is too small for the design: " + std::to_string(coarse.size()) +
                                                  " points at the design's sampling of " + decimal_text(leaf, 3) + " mm");
  const std::vector<Eigen::Matrix4d> candidates =
      principal_axes_candidates(design_frame, principal_frame(coarse), o.moment_tolerance);
  r.candidates = candidates.size();
  clock.lap("scan thinning, principal axes");
  // Cells of half the voxel: "near" is within half a voxel surely, and never beyond 1.75 voxels.
  const NearSurfaceCells cells(target.points, design.bbox,
                               std::max(leaf / 2, std::sqrt(area / double(target.points.size()))));
  clock.lap("near-surface cells");
  std::vector<Fit> fits = race_candidates(icp, cells, distance, coarse, candidates, size, leaf);
  std::stable_sort(fits.begin(), fits.end(), better);
  // A partial scan's principal axes need not match the design's, so the candidates can miss a pose that fits as
  // well as the best (one view of a part whose seen side is symmetric, turned half a turn about that side's own
  // centre). Such a second minimum sits at a symmetry of the design's or the seen surface's principal frame from the
  // best pose: those poses are raced too, so that an equal fit there is found and reported as an ambiguity.
  const Eigen::Matrix4d first = rigid_inverse(fits.front().scan_to_design);
  // About the design's free axis every 10 degrees (a turn-over axis then lies within 2.5 degrees of a symmetry's);
  // about the seen surface's every 30 (it is the scan's, and raced on every registration).
  std::vector<Eigen::Matrix4d> probes = principal_symmetry_probes(first, design_frame, o.moment_tolerance, 10);
  for (const Eigen::Matrix4d& p : principal_symmetry_probes(
           first, principal_frame(transformed_points(fits.front().scan_to_design, coarse)), o.moment_tolerance, 30))
    probes.push_back(p);
  std::vector<Fit> probed = race_candidates(icp, cells, distance, coarse, probes, size, leaf, fits.front().share);
  std::stable_sort(probed.begin(), probed.end(), better);
  r.candidates += probed.size();
  clock.lap("candidates (coarse ICP, fitness)");
  r.global_seconds = seconds_since(start);

  // Fine: the leaders of the coarse races refined on the fine points.
  const auto fine_start = std::chrono::steady_clock::now();
  const std::vector<Vec3> fine = thin_evenly(scan.points, o.fine_points);
  r.scan_points_used = fine.size();
  // The pairing distance shrinks from the coarse fit's reach to the inlier distance; the first steps need few
  // points, only the last one all of the fine set.
  const std::vector<Vec3> middle = thin_evenly(fine, std::max<size_t>(o.fine_points / 4, 50));
  clock.lap("scan thinning, principal axes");
  std::vector<Vec3> in_design;            // the fine points through the best pose
  std::vector<SurfaceDistance> nearest;   // and their nearest design points
  const auto settle = [&](const Eigen::Matrix4d& t0) {
    const Eigen::Matrix4d t = icp.align(middle, t0, std::max(2 * leaf, 4 * o.inlier_distance), 30);
    return icp.align(middle, t, 2 * o.inlier_distance, 30);
  };
  const auto refine = [&](const Eigen::Matrix4d& settled) {
    const Eigen::Matrix4d t = icp.align(fine, settled, o.inlier_distance, 15);
    clock.lap("fine ICP");
    in_design = transformed_points(t, fine);
    const Fit fit = measure(distance, in_design, t, o.inlier_distance, nearest);
    clock.lap("fine fitness");
    return fit;
  };
  // The distinct poses that fit about as well as the first at the coarse level are each refined, and the best fine
  // fit wins: at a voxel's reach the coarse ranking cannot tell a near miss from the truth. Those that fit about as
  // well as the winner at the fine level are its alternatives.
  constexpr size_t kMostRefined = 4, kMostProbes = 2;
  constexpr double kCoarseMargin = 0.05;
  struct Refined {
    Fit fit;
    std::vector<Vec3> in_design;
    std::vector<SurfaceDistance> nearest;
  };
  std::vector<Refined> refined;
  std::vector<Eigen::Matrix4d> distinct, settled;
  // The leaders of each race (the probes' own, so that they cannot crowd out the first race's).
  for (const auto& [race, most] : {std::pair{&fits, kMostRefined}, {&probed, kMostProbes}}) {
    size_t taken = 0;
    for (const Fit& f : *race) {
      if (taken == most || f.share < race->front().share - kCoarseMargin) break;  // sorted
      if (std::any_of(distinct.begin(), distinct.end(), [&](const auto& d) { return same_pose(d, f.scan_to_design, leaf); }))
        continue;
      distinct.push_back(f.scan_to_design);
      ++taken;
      // Two leaders that settle on one pose at the middle reach (to a tenth of the inlier distance and of a degree)
      // would refine to the same fit.
      const Eigen::Matrix4d at = settle(f.scan_to_design);
      if (std::any_of(settled.begin(), settled.end(),
                      [&](const auto& p) { return same_pose(p, at, 0.1 * o.inlier_distance, 0.1); }))
        continue;
      settled.push_back(at);
      const Fit fit = refine(at);
      refined.push_back({fit, std::move(in_design), std::move(nearest)});
    }
  }
  const auto winner = std::min_element(refined.begin(), refined.end(),
                                       [](const Refined& a, const Refined& b) { return better(a.fit, b.fit); });
  const Fit best = winner->fit;
  const std::vector<Vec3>& best_in_design = winner->in_design;
  for (const Refined& alt : refined)
    if (&alt != &*winner && r.alternatives.size() < 5 && alt.fit.share >= best.share - o.ambiguity_share &&
        alt.fit.rms <= o.ambiguity_rms * best.rms + 1e-3 &&
        std::none_of(r.alternatives.begin(), r.alternatives.end(),
                     [&](const auto& t) { return same_pose(rigid_inverse(t), alt.fit.scan_to_design, o.inlier_distance); }) &&
        !same_pose(alt.fit.scan_to_design, best.scan_to_design, o.inlier_distance))
      r.alternatives.push_back(rigid_inverse(alt.fit.scan_to_design));
  r.transform = rigid_inverse(best.scan_to_design);
  // A symmetry of the design gives a pose that fits exactly as well, whatever the scan shows.
  for (const Eigen::Matrix4d& s : symmetries) {
    const Eigen::Matrix4d alt = r.transform * s;
    if (r.alternatives.size() < 5 &&
        std::none_of(r.alternatives.begin(), r.alternatives.end(),
                     [&](const auto& t) { return same_pose(t, alt, o.inlier_distance); }))
      r.alternatives.push_back(alt);
  }
  r.rms = best.rms;
  r.inlier_share = best.share;
  r.overlap = covered_share(thin_evenly(target.points, 5000), best_in_design,
                             o.inlier_distance + 2 * std::sqrt(area / double(fine.size())));
  clock.lap("overlap");
  r.information = pose_information(icp.pairs(fine, estimate_normals(fine), best.scan_to_design, o.inlier_distance,
                                             o.information.outline_degrees),
                                   centre, design_frame.axes, 0.5 * size, icp.spacing(), o.information);
  // A design that every turn about an axis maps onto itself (a turned part whose facets are finer than the
  // symmetry's tolerance: a symmetric turn, and half of it too) fixes no turn about that axis: the facet kinks'
  // information is the sampling's chance. A discrete symmetry (a five-armed part) leaves the turn well fixed.
  const std::vector<Vec3> probe_points = thin_evenly(target.points, 2000);
  for (const Eigen::Matrix4d& sym : symmetries) {
    const Eigen::AngleAxisd turn(Eigen::Matrix3d(sym.topLeftCorner<3, 3>()));
    if (!(turn.angle() < M_PI / 2)) continue;
    // The half turn about the same line: its point c solves (I - R) c = t.
    const Vec3 c = (Eigen::Matrix3d::Identity() - turn.toRotationMatrix())
                       .completeOrthogonalDecomposition()
                       .solve(Vec3(sym.topRightCorner<3, 1>()));
    const Eigen::Matrix3d half = Eigen::AngleAxisd(turn.angle() / 2, turn.axis()).toRotationMatrix();
    Eigen::Matrix4d halfway = Eigen::Matrix4d::Identity();
    halfway.topLeftCorner<3, 3>() = half;
    halfway.topRightCorner<3, 1>() = c - half * c;
    if (maps_onto_itself(distance, probe_points, halfway, symmetry_options(o)))
      widen_for_symmetry(r.information, turn.axis(), turn.angle() / 2 * 180 / M_PI);
  }
  r.translation_sigma = r.information.translation_sigma;
  r.rotation_sigma_deg = r.information.rotation_sigma_deg;
  clock.lap("uncertainty");
  r.fine_seconds = seconds_since(fine_start);

  std::ostringstream why;
  if (!symmetries.empty())
    why << "the design maps onto itself under " << symmetries.size() << " motion" << (symmetries.size() > 1 ? "s" : "")
        << " (e.g. " << describe_motion(symmetries.front()) << " in its own frame): a pose and its symmetric ones put the same surface in "
        << "the same place; ";
  if (!r.alternatives.empty()) {
    why << r.alternatives.size() + 1 << " distinct poses fit about equally (inlier share within "
        << o.ambiguity_share << ", RMS within a factor " << o.ambiguity_rms << ")";
    const int equal = near_equal_moments(design_frame.moments, o.moment_tolerance);
    if (equal) why << "; the design has " << equal << " near-equal principal moments (a symmetric part)";
  }
  if (r.information.ambiguous()) {
    if (why.tellp() > 0) why << "; ";
    why << "the scanned surface fixes the pose only weakly along: " << r.information.describe()
        << "; in the scan's frame:";
    for (const PoseDirection& d : r.information.weak)
      why << " " << (d.rotation ? "turn about " : "slide along ") << vector_text(r.transform.topLeftCorner<3, 3>() * d.axis);
  }
  r.ambiguity = why.str();
  r.ambiguous = !r.ambiguity.empty();

  if (r.inlier_share < o.min_inlier_share)
    throw Error(kWhere, "refused: only " + decimal_text(100 * r.inlier_share, 1) + "% of the scan lies within " +
                            decimal_text(o.inlier_distance, 3) + " mm of the design (minimum " +
                            decimal_text(100 * o.min_inlier_share, 1) + "%): the scan does not show this part, or shows "
                            "much besides it (crop the table and clamps)");
  if (r.rms > o.max_rms)
    throw Error(kWhere, "refused: the RMS distance " + decimal_text(r.rms, 4) + " mm exceeds the maximum " +
                            decimal_text(o.max_rms, 4) + " mm");
  if (r.overlap < o.min_overlap)
    throw Error(kWhere, "refused: the scan covers " + decimal_text(100 * r.overlap, 1) + "% of the design (minimum " +
                            decimal_text(100 * o.min_overlap, 1) + "%)");
  return r;
}

std::string format_registration(const RegistrationResult& r) {
  std::ostringstream s;
  s << "transform (design -> scan, mm, row-major):\n";
  for (int i = 0; i < 4; ++i)
    s << "  " << decimal_text(r.transform(i, 0), 9) << ' ' << decimal_text(r.transform(i, 1), 9) << ' ' << decimal_text(r.transform(i, 2), 9)
      << ' ' << decimal_text(r.transform(i, 3), 6) << '\n';
  s << "rms: " << decimal_text(r.rms, 5) << " mm\ninlier share: " << decimal_text(r.inlier_share, 4) << "\noverlap: "
    << decimal_text(r.overlap, 4) << "\nuncertainty (1 sigma, worst direction): " << r.translation_sigma << " mm, "
    << r.rotation_sigma_deg << " deg\n" << format_pose_information(r.information) << "ambiguous: " << (r.ambiguous ? "yes (" + r.ambiguity + ")" : std::string("no")) << "\ncandidates: "
    << r.candidates << ", scan points used: " << r.scan_points_used << "\ntime: global " << decimal_text(r.global_seconds, 3)
    << " s, fine " << decimal_text(r.fine_seconds, 3) << " s\n";
  return s.str();
}

}  // namespace rosmill::core::scan
