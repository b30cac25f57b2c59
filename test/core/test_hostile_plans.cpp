// Plans under hostile requests: work beyond the policy (rosmill/work_bound.hpp) refused by every strategy before
// it allocates, with the estimate and the limit; nonsense values refused naming the field and its range;
// a mesh of degenerate triangles refused; the reachable fraction never above one.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <string>

#include "cli_run.hpp"
#include "error_of.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/segment/egi.hpp"
#include "rosmill/segment/setup_segmentation.hpp"
#include "rosmill/segment/surface_patches.hpp"
#include "rosmill/slice/slicer.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"

using namespace rosmill::core;
using namespace rosmill::core::segment;

namespace {

const char* const kStrategies[] = {"raster", "waterline", "rough", "grid-rough", "contour"};

PlanningRequest request(const Mesh& mesh, const std::string& strategy) {
  PlanningRequest r;
  r.input.mesh = &mesh;
  r.strategy = strategy;
  r.params.tool.cutter = Cutter::flat(6);
  return r;
}

// Refused within a second, with the estimate and the limit in the message.
void expect_refused_fast(const PlanningRequest& r, const std::string& what) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e = error_of([&] { plan(r); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_NE(e.find(r.strategy + ": would "), std::string::npos) << what << ": " << e;
  EXPECT_NE(e.find("(limit "), std::string::npos) << what << ": " << e;
  EXPECT_LT(seconds, 1.0) << what;
}

}  // namespace

TEST(WorkBound, AFourTriangleMeshAMillionMetresAcrossIsRefusedByEveryStrategy) {
  const double s = 1e9;  // mm
  const std::vector<Vec3> tetra = {{0, 0, 0}, {0, s, 0}, {s, 0, 0}, {0, 0, 0}, {s, 0, 0}, {0, 0, s},
                                   {0, 0, 0}, {0, 0, s}, {0, s, 0}, {s, 0, 0}, {0, s, 0}, {0, 0, s}};
  const Mesh mesh = build_mesh(tetra);
  ASSERT_EQ(mesh.face_count(), 4u);
  for (const char* strategy : kStrategies) expect_refused_fast(request(mesh, strategy), strategy);
}

TEST(WorkBound, AMicrometreStepoverOrStepDownIsRefusedByEveryStrategy) {
  const Mesh cube = make_primitive("cube");
  for (const char* strategy : kStrategies) {
    PlanningRequest r = request(cube, strategy);
    r.params.stepover = 1e-6;
    r.params.stepdown = 1e-6;
    expect_refused_fast(r, strategy);
  }
  // The same plans at ordinary values run.
  for (const char* strategy : kStrategies) EXPECT_FALSE(plan(request(cube, strategy)).empty()) << strategy;
}

TEST(WorkBound, TheErrorGivesTheCountsAndThePartSize) {
  const Mesh cube = make_primitive("cube");
  PlanningRequest r = request(cube, "raster");
  r.params.stepover = 1e-6;
  const std::string e = error_of([&] { plan(r); });
  EXPECT_NE(e.find("lines x"), std::string::npos) << e;
  EXPECT_NE(e.find("over a part of 60 x 60 mm"), std::string::npos) << e;
}

TEST(WorkBound, SlicingAtANanometreStepIsRefused) {
  const Mesh cube = make_primitive("cube");
  const std::string e = error_of([&] { planes_by_step(cube, 1e-9, "--step"); });
  EXPECT_NE(e.find("--step: would"), std::string::npos) << e;
  EXPECT_NE(e.find("planes"), std::string::npos) << e;
}

TEST(WorkBound, PlanWithAMicrometreStepoverFailsQuicklyOnTheCommandLine) {
  const std::string stl = ::testing::TempDir() + "/hostile_cube_" + std::to_string(::getpid()) + ".stl";
  ASSERT_EQ(run_rosmill_shell("primitive cube -o " + stl + " >/dev/null 2>&1").status, 0);
  const auto t0 = std::chrono::steady_clock::now();
  const CliRun run = run_rosmill_shell("plan " + stl + " --strategy raster --tool flat:6 --stepover 0.000001 2>&1");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  EXPECT_EQ(run.status, 1) << run.out;
  EXPECT_NE(run.out.find("drop-cutter queries (limit 2e+08)"), std::string::npos) << run.out;
  std::remove(stl.c_str());
}

TEST(PlanValidation, NonsenseValuesAreRefusedNamingTheFieldAndItsRange) {
  const Mesh cube = make_primitive("cube");
  struct Case {
    std::function<void(PlanningRequest&)> set;
    std::string expected;
  };
  const Case cases[] = {
      {[](PlanningRequest& r) { r.params.allowance = 1000; }, "parameter allowance: must lie in [0, 50] mm, got 1000"},
      {[](PlanningRequest& r) { r.params.stock_margin = 1e9; }, "parameter stock_margin: must lie in [0, 1000] mm"},
      {[](PlanningRequest& r) { r.params.angle_deg = 1e9; }, "parameter angle: must lie in [-360, 360] degrees"},
      {[](PlanningRequest& r) { r.params.tool.cutter = Cutter::bull(6, -1); },
       "parameter tool corner_radius: must lie in [0, 3] mm"},
      {[](PlanningRequest& r) { r.params.tool.cutter.diameter = NAN; },
       "parameter tool diameter: must lie in (0, 500]"},
      {[](PlanningRequest& r) { r.params.tool.feed = INFINITY; }, "parameter tool feed: must lie in (0, 100000]"},
      {[](PlanningRequest& r) { r.params.stepover = INFINITY; }, "parameter stepover: must lie in (0, 500] mm"},
      {[](PlanningRequest& r) { r.params.stepdown = -1; }, "parameter stepdown: must lie in (0, 500] mm"},
      {[](PlanningRequest& r) { r.params.allowance = NAN; }, "parameter allowance: must lie in [0, 50] mm, got nan"},
      {[](PlanningRequest& r) { r.params.angle_deg = NAN; }, "parameter angle"},
      {[](PlanningRequest& r) { r.params.stock_margin = NAN; }, "parameter stock_margin"},
      {[](PlanningRequest& r) { r.params.safe_clearance = INFINITY; },
       "parameter safe_clearance: must lie in (0, 1000]"},
      {[](PlanningRequest& r) { r.params.tolerance = 1e-300; }, "parameter tolerance"},
      {[](PlanningRequest& r) { r.input.setup.placement.pose.linear()(0, 0) = NAN; },
       "setup: the placement of 'workpiece' in 'setup +Z' is not finite"},
      {[](PlanningRequest& r) { r.input.setup.tool_axis = Vec3(NAN, 0, 1); },
       "setup: the tool axis must be a finite unit vector"},
  };
  for (const char* strategy : {"raster", "rough"})
    for (const Case& c : cases) {
      PlanningRequest r = request(cube, strategy);
      c.set(r);
      const std::string e = error_of([&] { plan(r); });
      EXPECT_NE(e.find(c.expected), std::string::npos) << strategy << ": expected '" << c.expected << "', got '" << e
                                                        << "'";
    }
}

TEST(PlanValidation, AToolpathFilesToolIsCheckedAsARequestsIs) {
  const std::string path = ::testing::TempDir() + "/hostile_tool_" + std::to_string(::getpid()) + ".json";
  Toolpath tp;
  tp.strategy = "raster";
  tp.tool.cutter = Cutter::bull(6, -1);
  tp.passes.push_back({"pass", {{Vec3(0, 0, 5), MoveType::Rapid, 0.0}}});
  write_toolpath_file(path, {tp});
  EXPECT_NE(error_of([&] { read_toolpath_file(path); }).find("toolpath 0: tool corner_radius: must lie in [0, 3] mm"),
            std::string::npos);
  std::remove(path.c_str());
}

TEST(PlanValidation, AMeshOfDegenerateTrianglesIsRefusedForPlanningAndSegmentation) {
  // Four triangles whose corners lie on one line: a bounding box, no surface.
  std::vector<Vec3> corners;
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) corners.emplace_back(10.0 * k + i, 5.0 * k + 0.5 * i, 2.0 * i);
  const Mesh flat = build_mesh(corners);
  ASSERT_EQ(flat.face_count(), 4u);
  for (const char* strategy : kStrategies)
    EXPECT_NE(error_of([&] { plan(request(flat, strategy)); }).find("plan: the part: every one of the mesh's 4 "
                                                                    "triangles is degenerate (zero area)"),
              std::string::npos)
        << strategy;
  EXPECT_NE(error_of([&] { segment_surface(flat); }).find("segmentation: the part: every one"), std::string::npos);
}

TEST(Segmentation, TheReachableFractionNeverExceedsOne) {
  for (const std::string& name : primitive_names()) {
    const Mesh mesh = make_primitive(name);
    const SurfacePatches sp = segment_surface(mesh);
    const EgiSet egis(sp);
    for (const char* setup : {"+z", "-x", "5axis"}) {
      const SetupSegmentation seg = segment_setup(egis, parse_setup(setup));
      EXPECT_LE(seg.reachable_fraction(), 1.0) << name << " " << setup;
      EXPECT_GE(seg.reachable_fraction(), 0.0) << name << " " << setup;
      EXPECT_NEAR(seg.reachable_fraction(), seg.reachable_area() / sp.total_area(), 1e-12) << name << " " << setup;
      if (std::string(setup) == "5axis") {
        EXPECT_EQ(seg.reachable_fraction(), 1.0) << name;
      }
    }
  }
}
