// Muslimin et al.'s plan straight from clouds: the presets cloud-rough, cloud-semi, cloud-finish and the template
// cloud-all (config/presets.yaml) through plan(request) on a CloudSurface.
//  - rapids only at or above the toolpath's clearance height (issue 7's rule; the machine limits refuse others);
//  - no cutter position puts the cutter into a point of the cloud (brute force over every point under it);
//  - the finish's cutter locations lie within the sampling bound of the mesh drop-cutter on the same (x, y);
//  - progress is reported and a callback that says stop cancels the plan;
//  - the real scans give complete rough, semi and finish toolpaths; the organised cloud with NaNs breaks nothing.
#include <gtest/gtest.h>

#include <fstream>

#include "rosmill/cloud/cloud_prep.hpp"
#include "rosmill/cloud/cloud_surface.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "plan_names.hpp"
#include "test_cloud_support.hpp"

using namespace rosmill::core;

namespace {

PointCloud cloud_of(std::vector<Vec3> pts) {
  PointCloud c;
  c.points = std::move(pts);
  c.recompute_bbox();
  return c;
}

// The package's presets with the semi-finish and finish stepovers changed.
PresetTable presets_with(double semi_stepover, double finish_stepover) {
  PresetTable t = test::package_presets();
  for (Preset& p : t.presets) {
    if (p.name == "cloud-semi") p.stepover = semi_stepover;
    if (p.name == "cloud-finish") p.stepover = finish_stepover;
    // Long enough out of the holder that the holder never meets the 50 mm dome: these tests check the cutter's
    // drops (the paper's), which a shorter tool's holder would lift beside the dome (tool_body_surface.hpp).
    p.tool.stick_out = 100;
  }
  return t;
}

// Quicker than the paper's finish (0.3 mm) for the brute-force checks; the tools and tolerance are the paper's.
PresetTable quick_presets() { return presets_with(2.5, 1.0); }

constexpr double kTolerance = 0.01;  // the presets' t

// The surface a plan at tolerance t builds (the sink allowed between points is t).
CloudSurfaceOptions surface_options(double t = kTolerance, HolePolicy holes = HolePolicy::Bridge,
                                    double hole_cell = 0) {
  CloudSurfaceOptions o;
  o.max_sink = t;
  o.holes = holes;
  o.hole_cell = hole_cell;
  return o;
}

// A preset or template on a surface, the presets' tools and tolerance.
Job plan_on(const Surface& s, const std::string& name, const PresetTable& presets,
            std::vector<PlanReport>* reports = nullptr, const PlanProgress& progress = {}) {
  PlanningRequest r;
  r.input.surface = &s;
  r.strategy = name;
  r.params.tolerance = NAN;
  r.presets = &presets;
  r.reports = reports;
  r.progress = progress;
  return plan(r);
}

// Every rapid ends at or above clearance_z, and one that moves sideways also starts there. Returns the number
// of descents at feed from the clearance height (the approaches).
size_t expect_rapids_above_clearance(const Toolpath& tp) {
  EXPECT_GE(tp.clearance_z, tp.safe_z - 1e-9) << tp.strategy;
  EXPECT_GE(tp.start.z(), tp.clearance_z - 1e-9) << tp.strategy;
  Vec3 at = tp.start;
  size_t descents = 0, rapids = 0;
  for (const ToolpathPass& pass : tp.passes)
    for (const Move& m : pass.moves) {
      if (m.type == MoveType::Rapid) {
        ++rapids;
        EXPECT_GE(m.to.z(), tp.clearance_z - 1e-9)
            << tp.strategy << " " << pass.name << ": rapid to " << m.to.transpose();
        if (m.to.head<2>() != at.head<2>()) {
          EXPECT_GE(at.z(), tp.clearance_z - 1e-9) << tp.strategy << " " << pass.name << ": sideways rapid from "
                                                    << at.transpose();
        }
      } else if (at.z() >= tp.clearance_z - 1e-9 && m.to.z() < at.z() && m.to.head<2>() == at.head<2>()) {
        ++descents;
        EXPECT_GT(m.feed, 0.0) << tp.strategy;
      }
      at = m.to;
    }
  EXPECT_GT(rapids, 0u) << tp.strategy;
  return descents;
}

}  // namespace

TEST(CloudPlan, NoRapidBelowTheClearanceHeightInAnyStrategy) {
  // A dome and a real model's vertices (the machine helper's rs274 test saw the rough rapid down to 1 mm over
  // the previous level): every strategy, the rough with several levels.
  const Mesh dome = make_primitive("dome");
  const Mesh part = read_stl(ROSMILL_TEST_DATA "/failedinpycam.stl");
  for (const PointCloud& cloud : {cloud_of(cloudtest::sample_mesh(dome, 2.0).pts), cloud_of(part.vertices)}) {
    PlanParams p;
    p.stepover = NAN;
    for (const char* strategy : {"cloud-rough", "cloud-semi", "cloud-finish", "cloud-all"}) {
      PlanParams q = p;
      if (std::string(strategy) == "cloud-finish") q.stepover = 1.0;  // quick
      if (std::string(strategy) == "cloud-all") q.tolerance = 0.05;
      PlanningRequest r;
      r.input.cloud = &cloud;
      r.strategy = strategy;
      r.params = q;
      r.presets = &test::package_presets();
      const Job job = plan(r);
      ASSERT_EQ(job.size(), std::string(strategy) == "cloud-all" ? 3u : 1u) << strategy;
      for (const Toolpath& tp : job) {
        const size_t descents = expect_rapids_above_clearance(tp);
        EXPECT_GT(descents, 0u) << strategy;
        // The rough's later levels descend at feed from the clearance height: the case this test is about.
        if (tp.strategy == "cloud-rough") {
          EXPECT_GE(tp.passes.size(), 2u) << "levels of " << strategy;
        }
      }
    }
  }
}

TEST(CloudPlan, NoCutterPositionGoesIntoAPoint) {
  // A noisy dome (sigma 0.02 mm) and a real model's sampling; every stage's moves checked at their ends and
  // three points inside each, against every point under the cutter (brute force, no grid). The ends of the
  // rough's moves keep the allowance delta from every point; the ball stages' cutter locations are exact drops
  // (no point inside), their moves at most the tolerance t in (the check of every move, cloud_sweep.hpp).
  const PresetTable presets = quick_presets();
  std::vector<PointCloud> clouds;
  {
    cloudtest::Sampling s = cloudtest::sample_mesh(make_primitive("dome"), 1.5);
    cloudtest::add_noise(s.pts, 0.02);
    clouds.push_back(cloud_of(s.pts));
  }
  clouds.push_back(cloud_of(cloudtest::sample_mesh(read_stl(ROSMILL_TEST_DATA "/failedinpycam.stl"), 1.5).pts));
  for (const PointCloud& cloud : clouds) {
    const CloudSurface s(cloud, surface_options());
    const cloudtest::SortedPoints brute(cloud.points);
    std::vector<PlanReport> reports;
    const Job job = plan_on(s, "cloud-all", presets, &reports);
    ASSERT_EQ(job.size(), 3u);
    const Preset* stages[3] = {presets.find("cloud-rough"), presets.find("cloud-semi"), presets.find("cloud-finish")};
    for (size_t k = 0; k < 3; ++k) {
      const Toolpath& tp = job[k];
      const double delta = stages[k]->allowance;
      const Cutter& c = stages[k]->tool.cutter;
      size_t checked = 0;
      for (const Vec3& cl : cloudtest::cut_positions(tp, 1)) {
        ASSERT_LE(brute.penetration(c, cl), (k == 0 ? -delta : 0.0) + 1e-9) << tp.strategy << " at " << cl.transpose();
        ++checked;
      }
      for (const Vec3& at : cloudtest::cut_positions(tp, 4))
        ASSERT_LE(brute.penetration(c, at), (k == 0 ? -delta : kTolerance - delta) + 1e-9)
            << tp.strategy << " inside a move at " << at.transpose();
      EXPECT_GT(checked, k == 0 ? 5u : 300u) << tp.strategy;
      EXPECT_EQ(reports[k].cl_points, tp.move_count()) << tp.strategy;
      EXPECT_GT(reports[k].samples, 400u) << tp.strategy;
    }
    // Every level down to the floor, d apart.
    const double height = s.bounds().size().z() - stages[0]->allowance;
    EXPECT_EQ(reports[0].levels, size_t(std::ceil(height / stages[0]->stepdown - 1e-9)));
  }
}

namespace {

// True when the move into or out of move i of the pass is vertical: the ends of the staircase steps where the
// cutter location jumps (a point met by the cutter's side), which are not drops of the cutter.
bool at_step(const ToolpathPass& pass, size_t i, const Vec3& before) {
  const Move& m = pass.moves[i];
  if (m.to.head<2>() == before.head<2>()) return true;
  return i + 1 < pass.moves.size() && pass.moves[i + 1].to.head<2>() == m.to.head<2>();
}


// A raw cloud (any units, NaNs allowed) in; the prepared cloud, the holes of its surface, the job of a preset or
// template (`tolerance` NaN: the presets') and its reports out.
struct CloudJob {
  PointCloud cloud;
  CloudPrepReport prep;
  std::vector<PlanReport> stages;
  std::vector<Hole> holes;
  Job job;
};

CloudJob plan_scan(const std::vector<Vec3>& raw, const CloudPrepOptions& prep, const PresetTable& presets,
                   double tolerance = NAN, const PlanProgress& progress = {}) {
  CloudJob cj;
  cj.cloud = prepare_cloud(raw, prep, &cj.prep);
  const CloudSurface s(cj.cloud, surface_options(std::isnan(tolerance) ? kTolerance : tolerance, HolePolicy::Bridge,
                                                 cj.prep.hole_cell));
  cj.holes = s.holes().holes();
  PlanningRequest r;
  r.input.surface = &s;
  r.strategy = "cloud-all";
  r.params.tolerance = tolerance;
  r.presets = &presets;
  r.reports = &cj.stages;
  r.progress = progress;
  cj.job = plan(r);
  return cj;
}

}  // namespace

TEST(CloudPlan, FinishWithinTheSamplingBoundOfTheMeshDropCutter) {
  // The finish planned on a cloud sampled from a mesh (lattice step 0.6 mm, covering radius rho = 0.6/sqrt(3),
  // noise sigma 0.02 mm, eta its largest displacement), against the mesh drop-cutter at each cutter location's
  // (x, y). The bound (test_cloud_support.hpp's sampling_bound) holds for every drop of the cloud: at least the
  // mesh drop of the ball eroded by rho + eta, less rho + eta (no mesh point can be in it, or a sample would be
  // within rho + eta of it, inside the ball); at most the mesh drop of the ball grown by the support disc and eta,
  // plus eta. Every finish location is such a drop except the top and foot of a vertical step (excluded, counted),
  // which lie above the drop: they are checked against the lower bound only.
  for (const std::string& name : {std::string("dome"), std::string("cavity")}) {
    const Mesh mesh = make_primitive(name);
    cloudtest::Sampling sm = cloudtest::sample_mesh(mesh, 0.6);
    const double eta = cloudtest::add_noise(sm.pts, 0.02);
    const PointCloud cloud = cloud_of(sm.pts);
    const PresetTable presets = presets_with(2.5, 3.0);
    const CloudSurface s(cloud, surface_options());
    const MeshSurface ref(mesh);
    const Toolpath tp = plan_on(s, "cloud-finish", presets).at(0);
    const Cutter& c = presets.find("cloud-finish")->tool.cutter;
    size_t compared = 0, steps = 0, floor = 0;
    Vec3 before = tp.start;
    for (const ToolpathPass& pass : tp.passes)
      for (size_t i = 0; i < pass.moves.size(); before = pass.moves[i].to, ++i) {
        const Move& m = pass.moves[i];
        if (m.type == MoveType::Rapid || m.to.z() >= tp.safe_z - 1e-9) continue;
        const cloudtest::Bound b = cloudtest::sampling_bound(ref, s, c, sm.covering, eta, m.to.x(), m.to.y());
        ASSERT_GE(m.to.z(), b.lo - 1e-9) << name << " at " << m.to.transpose();
        if (at_step(pass, i, before)) {
          ++steps;
          continue;
        }
        // At the floor (nothing under the ball, or its tip would hang below the cloud's lowest point) the
        // location is the floor, not a drop.
        if (m.to.z() <= s.bounds().min.z() + 1e-9) {
          ++floor;
          continue;
        }
        if (!b.misses) {
          ASSERT_LE(m.to.z(), b.hi + 1e-9) << name << " at " << m.to.transpose();
        }
        ++compared;
      }
    EXPECT_GT(compared, 500u) << name;
    EXPECT_LT(steps, compared / 10) << name;
    EXPECT_GT(floor, 0u) << name;  // the lines run past the part
  }
}

TEST(CloudPlan, ProgressIsReportedAndCancelStopsThePlan) {
  const PointCloud cloud = cloud_of(cloudtest::sample_mesh(make_primitive("dome"), 2.0).pts);
  const PresetTable presets = quick_presets();
  const CloudSurface s(cloud, surface_options());
  std::vector<double> seen;
  const Job job = plan_on(s, "cloud-all", presets, nullptr, [&](double f) { seen.push_back(f); return true; });
  ASSERT_EQ(job.size(), 3u);
  ASSERT_GT(seen.size(), 20u);
  for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1] - 1e-12);
  EXPECT_NEAR(seen.back(), 1.0, 1e-12);
  // Stop once past a third: the plan throws "cancelled" and no call comes after the one that said stop.
  size_t calls = 0, stop_call = 0;
  try {
    plan_on(s, "cloud-all", presets, nullptr, [&](double f) {
      ++calls;
      if (f > 0.35 && !stop_call) stop_call = calls;
      return !stop_call;
    });
    FAIL() << "not cancelled";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cancelled"), std::string::npos) << e.what();
  }
  EXPECT_GT(stop_call, 0u);
  EXPECT_EQ(calls, stop_call);
  // A raw cloud prepared and planned cancels the same way during any stage, and plans all three otherwise.
  CloudPrepOptions prep;
  EXPECT_THROW(plan_scan(cloud.points, prep, presets, NAN, [](double f) { return f < 0.5; }), Error);
  const CloudJob cj = plan_scan(cloud.points, prep, presets);
  ASSERT_EQ(cj.job.size(), 3u);
  ASSERT_EQ(cj.stages.size(), 3u);
  EXPECT_EQ(cj.job[0].strategy, "cloud-rough");
  EXPECT_EQ(cj.job[1].strategy, "cloud-semi");
  EXPECT_EQ(cj.job[2].strategy, "cloud-finish");
  EXPECT_EQ(cj.prep.points_out, cloud.points.size());
}

namespace {

// Complete toolpaths on a real scan: every stage has moves, stays over the cloud's plan-view box (grown by the
// reach of the cutter and the entry), keeps its rapids at the clearance, and its raster lines cover the cloud
// across (the first and last line within a stepover of the box's edges).
void expect_complete(const CloudJob& cj, const std::string& name) {
  ASSERT_EQ(cj.job.size(), 3u) << name;
  const Box3& box = cj.cloud.bbox;
  for (size_t k = 0; k < 3; ++k) {
    const Toolpath& tp = cj.job[k];
    const double reach = tp.tool.cutter.radius() + 1.0;
    EXPECT_GT(tp.move_count(), 1000u) << name << " " << tp.strategy;
    EXPECT_GT(cj.stages[k].lines, 5u) << name << " " << tp.strategy;
    expect_rapids_above_clearance(tp);
    double ylo = INFINITY, yhi = -INFINITY, zlo = INFINITY;
    for (const ToolpathPass& pass : tp.passes)
      for (const Move& m : pass.moves) {
        ASSERT_GE(m.to.x(), box.min.x() - reach) << name << " " << tp.strategy;
        ASSERT_LE(m.to.x(), box.max.x() + reach) << name << " " << tp.strategy;
        ASSERT_GE(m.to.y(), box.min.y() - reach) << name << " " << tp.strategy;
        ASSERT_LE(m.to.y(), box.max.y() + reach) << name << " " << tp.strategy;
        ASSERT_LE(m.to.z(), tp.safe_z + 1e-9) << name << " " << tp.strategy;
        if (m.type == MoveType::Rapid) continue;
        ylo = std::min(ylo, m.to.y()), yhi = std::max(yhi, m.to.y()), zlo = std::min(zlo, m.to.z());
      }
    const double across = k == 0 ? tp.tool.cutter.diameter : (k == 1 ? 4.0 : 3.0);
    EXPECT_LE(ylo, box.min.y() + across) << name << " " << tp.strategy;
    EXPECT_GE(yhi, box.max.y() - across) << name << " " << tp.strategy;
    EXPECT_GE(zlo, box.min.z() - 1e-6) << name << " " << tp.strategy << " goes below the cloud";
  }
  EXPECT_GT(cj.stages[0].levels, 1u) << name;
}

// The finish's 0.3 mm takes seconds on these scans (bench_cloud measures it).
PresetTable scan_presets() { return presets_with(4.0, 3.0); }

}  // namespace

TEST(CloudPlan, RealScansGiveCompleteRoughSemiAndFinish) {
  for (const char* file : {"snp_part_scan.ply", "snp_blending_part_scan.ply"}) {
    const PointCloud raw = read_cloud(std::string(ROSMILL_TEST_DATA "/") + file);  // metres
    const CloudJob cj = plan_scan(raw.points, CloudPrepOptions{}, scan_presets());
    EXPECT_EQ(cj.prep.points_out, raw.points.size()) << file;
    EXPECT_GT(cj.cloud.bbox.size().x(), 100.0) << file << ": read in metres, planned in mm";
    expect_complete(cj, file);
  }
}

TEST(CloudPlan, NoetherRawMeshScanFromSharedData) {
  const std::string path = ROSMILL_SHARED_DATA "/cloud/noether_raw_mesh.ply";
  if (!std::ifstream(path)) GTEST_SKIP() << path << " is absent (shared data not mounted): not checked";
  const PointCloud raw = read_cloud(path);
  const CloudJob cj = plan_scan(raw.points, CloudPrepOptions{}, presets_with(8.0, 6.0));
  expect_complete(cj, "noether_raw_mesh.ply");
  EXPECT_FALSE(cj.holes.empty());  // its open middle is reported and bridged
}

TEST(CloudPlan, OrganisedCloudWithNaNsBreaksNothing) {
  CloudInfo info;
  const PointCloud raw = read_cloud(ROSMILL_TEST_DATA "/pcl_table_scene_mug_stereo_textured.pcd", {}, &info);
  CloudPrepOptions prep;
  prep.voxel = 5.0;  // the table scene is 1.4 m across: a coarse cloud keeps the test quick
  const CloudJob cj = plan_scan(raw.points, prep, presets_with(15.0, 15.0), 0.1);
  EXPECT_EQ(cj.prep.dropped_nonfinite, 0u);  // read_cloud drops them already (test_cloud_io counts them)
  EXPECT_LT(cj.prep.after_voxel, raw.points.size());
  ASSERT_EQ(cj.job.size(), 3u);
  for (const Toolpath& tp : cj.job) {
    expect_rapids_above_clearance(tp);
    for (const ToolpathPass& pass : tp.passes)
      for (const Move& m : pass.moves) ASSERT_TRUE(m.to.allFinite()) << tp.strategy;
  }
  // The raw organised points, NaNs and all, given to the API directly: dropped and counted.
  std::vector<Vec3> with_nan = raw.points;
  with_nan.insert(with_nan.end(), 1000, Vec3(NAN, NAN, NAN));
  CloudPrepReport r;
  const PointCloud kept = prepare_cloud(with_nan, CloudPrepOptions{}, &r);
  EXPECT_EQ(r.dropped_nonfinite, 1000u);
  EXPECT_EQ(kept.points.size(), raw.points.size());
}

TEST(CloudPlan, HolesAreBridgedOrSkippedNeverPlungedInto) {
  // Level ground at z = 4 (0.5 mm pitch, 60 x 40 mm) with an 8 x 8 mm hole of missing data, a block 10 mm
  // high (work for the rough) away from it, and the floor below.
  std::vector<Vec3> pts;
  for (double x = 0; x <= 60 + 1e-9; x += 0.5)
    for (double y = 0; y <= 40 + 1e-9; y += 0.5)
      if (!(x > 26 && x < 34 && y > 16 && y < 24))
        pts.push_back(Vec3(x, y, x >= 4 && x <= 16 && y >= 5 && y <= 35 ? 14.0 : 4.0));
  pts.push_back(Vec3(0, 0, 0));  // the floor
  const PointCloud cloud = cloud_of(pts);
  const PresetTable presets = quick_presets();
  const CloudSurface s(cloud, surface_options());
  ASSERT_EQ(s.holes().holes().size(), 1u);
  const Hole& hole = s.holes().holes()[0];
  EXPECT_NEAR(hole.lid_z, 4.0, 1e-9);
  // Bridge: the finish crosses the hole on its lid: cutter locations on it, moves within the tolerance t.
  std::vector<PlanReport> reports;
  const Toolpath bridged = plan_on(s, "cloud-finish", presets, &reports).at(0);
  EXPECT_EQ(reports.at(0).skipped_samples, 0u);
  // Over the lid: positions whose axis is over the hole's cells (hole.box), which the lid covers. (The missing
  // data reaches a little past those coarse cells; a cutter whose axis is out there hangs over a gap no lid
  // covers and may sink into it.)
  size_t over = 0;
  for (const Vec3& p : cloudtest::cut_positions(bridged, 2))
    if (p.x() > hole.box.min.x() && p.x() < hole.box.max.x() && p.y() > hole.box.min.y() && p.y() < hole.box.max.y()) {
      ASSERT_GE(p.z(), 4.0 - kTolerance - 1e-9) << p.transpose();  // moves stay within t of the surface
      ++over;
    }
  EXPECT_GT(over, 10u);
  // Skip: no cutting position has the cutter's footprint over the hole; the samples left out are reported.
  const CloudSurface skipping(cloud, surface_options(kTolerance, HolePolicy::Skip));
  for (const char* stage : {"cloud-rough", "cloud-finish"}) {
    reports.clear();
    const Toolpath tp = plan_on(skipping, stage, presets, &reports).at(0);
    EXPECT_GT(reports.at(0).skipped_samples, 0u) << tp.strategy;
    const double reach = presets.find(stage)->tool.cutter.radius();
    size_t cutting = 0;
    for (const Vec3& p : cloudtest::cut_positions(tp, 1)) {
      if (p.z() >= tp.safe_z - 1e-9) continue;
      ASSERT_FALSE(s.holes().disc_touches_hole(p.x(), p.y(), reach - 1e-6)) << tp.strategy << " at " << p.transpose();
      ++cutting;
    }
    EXPECT_GT(cutting, 50u) << tp.strategy;
    expect_rapids_above_clearance(tp);
  }
}
