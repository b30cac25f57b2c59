// Every strategy's chords round the part's convex corners within the plan's tolerance, checked by code that shares
// none with the planners: the toolpaths swept as swept_check.hpp sweeps a cutter (the least height of its bottom
// over a point, by golden-section search), over samples of the design's surface just inside it. The parts have
// convex corners of every kind: the bracket (a wall standing on a plate, a groove whose ends stop short of the
// wall's sides: vertical and horizontal convex edges) and the cone (a round edge on the table).
#include <gtest/gtest.h>

#include <string>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/setups/reach.hpp"
#include "rosmill/testing/sanitized.hpp"
#include "rosmill/testing/swept_check.hpp"

using namespace rosmill::core;

namespace {

struct Case {
  std::string strategy;
  Cutter cutter;
  double stepover, stepdown;
};

// Samples of the part's surface that some move cut deeper than `depth` below it.
size_t cut_below(const Mesh& part, const Job& job, double depth, Vec3& worst) {
  swept_check::SweptJob swept;
  swept.add(SetupFrame{}, job);
  const setups::SurfaceSamples s = setups::sample_surface(part, rosmill::testing::kSanitized ? 2.0 : 0.5);
  size_t n = 0;
  for (size_t k = 0; k < s.size(); ++k)
    if (swept.swept(s.points[k] - depth * s.normals[k])) ++n, worst = s.points[k];
  return n;
}

}  // namespace

TEST(PlanCorners, EveryStrategyKeepsOutOfConvexCornersWithinTheTolerance) {
  const Mesh bracket = read_stl(ROSMILL_TEST_DATA "/parts/bracket.stl");
  const Mesh cone = make_primitive("cone");
  const std::vector<Case> cases = {{"raster", Cutter::ball(6), 1.0, 1.0},   {"raster", Cutter::flat(6), 2.0, 1.0},
                                   {"waterline", Cutter::flat(6), 2.0, 2.0}, {"waterline", Cutter::ball(6), 2.0, 2.0},
                                   {"rough", Cutter::flat(10), 4.0, 5.0},    {"adaptive", Cutter::flat(10), 4.0, 8.0},
                                   {"contour", Cutter::flat(6), 2.0, 4.0}};
  for (const Mesh* part : {&bracket, &cone})
    for (const Case& c : cases) {
      PlanningRequest r;
      r.input.mesh = part;
      r.strategy = c.strategy;
      r.params.tool = default_tool(c.cutter);
      r.params.tool.stick_out = 100;  // the holder clear of these parts: the check is of the cutter
      r.params.stepover = c.stepover;
      r.params.stepdown = c.stepdown;
      r.params.allowance = c.strategy == "rough" || c.strategy == "adaptive" ? 0.5 : 0.0;
      r.params.tolerance = 0.001;
      const Job job = plan(r);
      Vec3 worst = Vec3::Zero();
      const size_t n = cut_below(*part, job, r.params.tolerance + 1e-4, worst);
      EXPECT_EQ(n, 0u) << c.strategy << " " << cutter_type_name(c.cutter.type) << " on a part of "
                       << part->face_count() << " facets: cut below the design at " << worst.transpose();
    }
}
