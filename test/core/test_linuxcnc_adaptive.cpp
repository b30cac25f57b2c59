// An adaptive clearing program on the REAL LinuxCNC (the stock sim/axis_mm machine, scripts/linuxcnc-sim): a
// short one, a ring of material around a small block at one level entered from the air beside it. The controller
// runs it to its end (its trajectory planner takes the many short moves and arcs) and the machine stops where the
// program's last move goes.
#include <gtest/gtest.h>

#include "rosmill/control/controller.hpp"
#include "rosmill/control/linuxcnc.hpp"
#include "rosmill/control/program_run.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/plan/adaptive.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "linuxcnc_simulator.hpp"

using namespace rosmill::core;
using namespace rosmill::core::control;

TEST(LinuxcncAdaptive, AShortAdaptiveProgramRunsToItsEnd) {
  // An 8 x 8 x 2 mm block in a box stock 1.5 mm larger each way: one level, 1.5 mm of material all round.
  const Mesh block = build_mesh(box_corners(Box3::between(Vec3(-4, -4, -2), Vec3(4, 4, 0))));
  const MeshSurface surface(block);
  PlanParams p;
  p.tool.id = 1;  // the simulator's tool table
  p.tool.cutter = Cutter::flat(4);
  p.tool.feed = 1500;
  p.tool.plunge_feed = 600;
  p.stepover = 1.2;
  p.stepdown = 4;
  p.stock_margin = 1.5;
  p.tolerance = 0.01;
  const gcode::MachineLimits machine = gcode::load_machine_limits(ROSMILL_SOURCE_DIR "/config/machine.yaml");
  p.max_feed = machine.max_feed;
  const Job job = adaptive_strategy(surface, p, {});
  ASSERT_FALSE(job.empty());
  gcode::PostOptions o;
  o.arcs = true;
  o.arc_tolerance = 0.01;
  gcode::ProgramChecks checks;
  checks.machine = machine;
  checks.rs274 = true;
  const std::vector<std::string> program = gcode::prepare_program(job, o, checks).program.lines;
  ASSERT_GT(program.size(), 50u);

  REQUIRE_SIMULATOR(sim);
  auto c = sim.controller();
  c->connect();
  const ControllerStatus s = run_to_end(*c, program, SendOptions{}, {}, 180.0);
  EXPECT_EQ(s.state, RunState::Finished);
  EXPECT_EQ(s.acknowledged_line, program.size());
  ASSERT_TRUE(s.position_known);
  // G43 adds the tool's length to machine Z.
  const Vec3 end = gcode::state_before(program, program.size()).position + Vec3(0, 0, sim.tool_length(1));
  EXPECT_LT((s.position - end).cwiseAbs().maxCoeff(), 0.002) << "machine at " << s.position.transpose();
  c->disconnect();
}
