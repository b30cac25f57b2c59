// Roughing: no level cuts into part + allowance (every CL and every 0.1 mm along every move against the
// independent reference over all triangles), levels from the stock top down by at most the step-down to the
// floor, and every entry into material a ramp no steeper than asked, never a straight plunge: a vertical plunge
// ends in air, at or above the level cleared before.
#include <gtest/gtest.h>

#include <cmath>

#include "rosmill/testing/sanitized.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/plan/rough.hpp"
#include "test_plan_check.hpp"

using namespace rosmill::core;
using namespace rosmill::core::test;

namespace {

struct Case {
  std::string name;
  Mesh mesh;
  Cutter cutter;
  double stepover, stepdown, allowance;
};

void check_rough(const Case& c) {
  SCOPED_TRACE(c.name);
  PlanParams p;
  p.tool = default_tool(c.cutter);
  p.stepover = c.stepover;
  p.stepdown = c.stepdown;
  p.allowance = c.allowance;
  RoughOptions o;
  o.ramp_slope = 0.1;
  const Job job = rough_on(MeshSurface(c.mesh), p, o);
  ASSERT_EQ(job.size(), 1u);
  const Toolpath& tp = job.at(0);
  const double top = c.mesh.bbox.max.z() + p.stock_margin, floor = c.mesh.bbox.min.z() + c.allowance;

  double above = top;  // the level cleared before the current pass
  size_t levels = 0, ramps = 0, plunges = 0;
  Vec3 at = tp.start;
  for (const ToolpathPass& pass : tp.passes) {
    double level = 1e300;
    for (const Move& m : pass.moves)
      if (m.type != MoveType::Rapid) level = std::min(level, m.to.z());
    if (level == 1e300) continue;
    ++levels;
    EXPECT_GE(level, floor - 1e-9) << pass.name;
    EXPECT_LE(above - level, c.stepdown + 1e-9) << pass.name;
    for (const Move& m : pass.moves) {
      const double run = (m.to - at).head<2>().norm(), fall = at.z() - m.to.z();
      if (m.type == MoveType::Plunge) {
        if (run < 1e-9) {
          ++plunges;
          EXPECT_GE(m.to.z(), above - 1e-9) << pass.name << ": a straight plunge into material at "
                                            << m.to.transpose();
        } else {
          ++ramps;
          EXPECT_LE(fall, o.ramp_slope * run + 1e-9) << pass.name << ": ramp too steep at " << m.to.transpose();
        }
      }
      if (m.type == MoveType::Feed) {
        EXPECT_LE(fall, 1e-9) << pass.name << ": a feed move goes down at " << m.to.transpose();
      }
      at = m.to;
    }
    above = level;
  }
  EXPECT_NEAR(above, floor, 1e-9);  // the last level is the floor
  EXPECT_GE(levels, static_cast<size_t>(std::floor((top - floor) / c.stepdown)));
  EXPECT_GT(ramps, 0u);
  std::printf("  %s: %zu levels, %zu ramp legs, %zu plunges in air\n", c.name.c_str(), levels, ramps, plunges);
  expect_no_gouge(tp, c.mesh, c.allowance, c.name);
}

}  // namespace

TEST(PlanRough, RealModels) {
  StlReadOptions inch;
  inch.units = Units::Inch;
  check_rough({"mount_rush flat 10", read_stl(ROSMILL_TEST_DATA "/mount_rush.stl"), Cutter::flat(10), 8.0, 4.0, 0.5});
  if (rosmill::testing::kSanitized) return;  // the same paths again, on a model of ten times the area
  check_rough({"ktoolcav (inch) flat 6", read_stl(ROSMILL_TEST_DATA "/ktoolcav.stl", inch), Cutter::flat(6), 8.0,
               12.0, 0.3});
}

TEST(PlanRough, Primitives) {
  for (const std::string name : {"cube", "cavity", "cone"})
    check_rough({name + " flat 10", make_primitive(name), Cutter::flat(10), 9.0, 12.0, 0.5});
}
