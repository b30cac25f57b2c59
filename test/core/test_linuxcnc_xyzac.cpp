// The trunnion's indexing checked against LinuxCNC's own xyzac-trt kinematics: for each setup direction the table is
// turned to the A and C rosmill solves, the tool is sent (identity kinematics, machine coordinates) to where rosmill's
// chain puts a point of the table, and the simulator, switched to tool-centre-point kinematics (M428), reports where
// the tip is on the table: the point itself, and 10 mm up the spindle the point 10 mm along the setup's tool axis.
// Then a 3+2 program (three setups, G53 retracts and G0 A C indexing) runs to its end and stops at its last point.
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>
#include <thread>

#include "linuxcnc_simulator.hpp"
#include "multi_axis_parts.hpp"
#include "rosmill/control/program_run.hpp"
#include "rosmill/gcode/cycle_time.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/gcode/rs274_check.hpp"
#include "rosmill/geometry/segment_distance.hpp"
#include "rosmill/machine/trunnion.hpp"
#include "rosmill/plan/five_axis_finish.hpp"
#include "test_post_jobs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::control;

namespace {

using Clock = std::chrono::steady_clock;

const machine::Trunnion& trunnion() {
  static const gcode::MachineLimits m =
      gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine_xyzac.yaml");
  return *m.trunnion;
}

// X Y Z A C as the controller reports them (abs_act_pos: X Y Z A B C ..., the kinematics' world coordinates).
std::vector<double> axes(LinuxcncController& c) {
  const std::string reply = c.get("abs_act_pos");
  std::istringstream in(reply);
  std::vector<double> v;
  for (double x; v.size() < 6 && in >> x;) v.push_back(x);
  if (v.size() < 6) {
    ADD_FAILURE() << "abs_act_pos gave fewer than 6 axes: " << reply;
    return std::vector<double>(5, NAN);
  }
  return {v[0], v[1], v[2], v[3], v[5]};
}

// The axes once the machine has come to rest (two reads 0.2 s apart agree), waiting at most `seconds`.
std::vector<double> at_rest(LinuxcncController& c, double seconds = 30.0) {
  std::vector<double> before = axes(c);
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    const std::vector<double> now = axes(c);
    double moved = 0;
    for (int k = 0; k < 5; ++k) moved = std::max(moved, std::abs(now[k] - before[k]));
    if (moved < 1e-6) return now;
    before = now;
  }
  ADD_FAILURE() << "the machine did not come to rest within " << seconds << " s";
  return before;
}

void mdi(LinuxcncController& c, const std::string& block) {
  c.set("mode mdi");
  c.set("mdi " + block);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the block is queued; at_rest waits for its end
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(6);
  s << std::fixed << v;
  return s.str();
}

Vec3 xyz(const std::vector<double>& v) { return Vec3(v[0], v[1], v[2]); }

}  // namespace

TEST(LinuxcncXyzac, IndexingAgreesWithTheSimulatorsKinematics) {
  REQUIRE_MACHINE_SIMULATOR(sim, "xyzac");
  auto c = sim.controller();
  c->connect();
  const machine::Trunnion& t = trunnion();
  const Vec3 p(6, -9, 24);  // a point of the table (mm, its frame at A = C = 0)
  machine::Index last;
  for (const Vec3& d : {Vec3(Vec3::UnitZ()), Vec3(Vec3::UnitX()), Vec3(-Vec3::UnitX()), Vec3(Vec3::UnitY()),
                        Vec3(-Vec3::UnitY())}) {
    SCOPED_TRACE("tool axis " + num(d.x()) + " " + num(d.y()) + " " + num(d.z()));
    const auto i = machine::index_for(t, d, last);
    ASSERT_TRUE(i);
    last = *i;
    mdi(*c, "M429");  // identity: the program's X Y Z are the joints (no part on the table: no retract needed)
    mdi(*c, "G0 A" + num(i->a) + " C" + num(i->c));
    std::vector<double> v = at_rest(*c);
    EXPECT_NEAR(v[3], i->a, 1e-4);
    EXPECT_NEAR(v[4], i->c, 1e-4);
    const Vec3 m = t.machine_point(p, i->a, i->c);
    mdi(*c, "G0 X" + num(m.x()) + " Y" + num(m.y()) + " Z" + num(m.z()));
    EXPECT_LT((xyz(at_rest(*c)) - m).cwiseAbs().maxCoeff(), 1e-4);
    mdi(*c, "M428");  // tool-centre-point: the controller reports the tip on the table
    v = at_rest(*c);
    EXPECT_LT((xyz(v) - p).cwiseAbs().maxCoeff(), 2e-3) << "the tip on the table at " << xyz(v).transpose();
    // 10 mm up the spindle is 10 mm along the setup's tool axis on the table.
    mdi(*c, "M429");
    mdi(*c, "G0 Z" + num(m.z() + 10));
    at_rest(*c);
    mdi(*c, "M428");
    v = at_rest(*c);
    EXPECT_LT((xyz(v) - (p + 10 * d)).cwiseAbs().maxCoeff(), 2e-3) << "10 mm up: " << xyz(v).transpose();
  }
  mdi(*c, "M429");
  at_rest(*c);
  c->disconnect();
}

TEST(LinuxcncXyzac, A32ProgramRunsToItsEndAtItsLastPoint) {
  // Three setups of short passes with tool 5 (30 mm long in the simulator's table): the top, then -Y and +X.
  Toolpath top;
  top.strategy = "top";
  top.tool.id = 5;
  top.tool.cutter = Cutter::flat(6);
  top.tool.feed = 1000;
  top.indexed = true;
  top.clearance_z = 50;
  top.start = Vec3(0, 0, 50);
  top.passes.push_back(test::pass_of({test::move_to(MoveType::Feed, Vec3(0, 0, 42), 600), test::move_to(MoveType::Feed, Vec3(20, 0, 42), 1000),
                         test::move_to(MoveType::Rapid, Vec3(20, 0, 50), 0)}));
  Toolpath side = top, end = top;
  side.strategy = "side";
  side.a = -90, side.c = 0;
  side.start = Vec3(0, 30, 60);
  side.clearance_z = 60;
  side.passes = {test::pass_of({test::move_to(MoveType::Feed, Vec3(0, 30, 52), 600), test::move_to(MoveType::Feed, Vec3(-15, 30, 52), 1000),
                   test::move_to(MoveType::Rapid, Vec3(-15, 30, 60), 0)})};
  end.strategy = "end";
  end.a = -90, end.c = -90;
  end.start = Vec3(5, 25, 60);
  end.clearance_z = 60;
  end.passes = {test::pass_of({test::move_to(MoveType::Feed, Vec3(5, 25, 54), 600), test::move_to(MoveType::Feed, Vec3(5, 40, 54), 1000),
                  test::move_to(MoveType::Rapid, Vec3(5, 40, 60), 0)})};
  gcode::PostOptions o;
  o.index_safe_z = trunnion().safe_z;
  o.work_offset = gcode::WorkOffset{};
  o.work_offset_note = "machine zero";
  const std::vector<std::string> program = gcode::post({top, side, end}, o).lines;
  const gcode::MachineLimits limits =
      gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine_xyzac.yaml");
  for (const gcode::LimitViolation& v : gcode::check_limits(program, limits))
    ADD_FAILURE() << "line " << v.line << " " << v.limit << ": " << v.detail << "\n" << program[v.line - 1];
  const gcode::Rs274Result rs = gcode::run_rs274(program);
  EXPECT_TRUE(rs.ok) << "line " << rs.error_line << ": " << rs.error;

  // The estimate of a 3+2 program, its G53 retracts and its A/C turns from rest to rest included: within 5 % (and
  // the 0.3 s a start and an end cannot be placed closer) of the simulator's machine time from its first motion to
  // its last (this one: 28.93 s against 28.22 s, +2.5 %; the bundled 3+2 job's program,
  // config/jobs/slotted_block_xyzac.yaml: 395.6 s against 393.0 s, +0.7 %).
  const double estimate = gcode::estimate_cycle_time(program, limits.trajectory).seconds;

  REQUIRE_MACHINE_SIMULATOR(sim, "xyzac");
  auto c = sim.controller();
  c->connect();
  const auto run = sim.run_timed(*c, program);  // to its end, or it throws
  std::printf("3+2 program: estimated %.2f s, the simulator %.2f s (%+.1f %%)\n", estimate, run.all,
              100 * (estimate - run.all) / run.all);
  EXPECT_NEAR(estimate, run.all, 0.05 * run.all + 0.3);
  const std::vector<double> v = at_rest(*c);
  // Identity kinematics: the machine's X Y Z are the program's, with G43 adding the tool's length to Z.
  const Vec3 last = gcode::state_before(program, program.size()).position + Vec3(0, 0, sim.tool_length(5));
  EXPECT_LT((xyz(v) - last).cwiseAbs().maxCoeff(), 2e-3) << xyz(v).transpose() << " vs " << last.transpose();
  EXPECT_NEAR(v[3], -90, 1e-4);
  EXPECT_NEAR(v[4], -90, 1e-4);
  c->disconnect();
}

namespace {

// The program's moves in tool-centre-point kinematics (after its M428, before its M429), as straight segments of
// the tip on the table with the A and C at their ends: what the controller is asked to follow.
struct TipSegment {
  Vec3 from, to;
  double a_from, a_to, c_from, c_to;
  size_t line;
};

std::vector<TipSegment> tool_centre_point_moves(const std::vector<std::string>& program) {
  std::vector<TipSegment> out;
  gcode::Interpreter reader;
  bool tcp = false;
  for (size_t i = 0; i < program.size(); ++i) {
    reader.read(program[i], i + 1);
    if (reader.block().has_m(428)) tcp = true;
    if (reader.block().has_m(429)) tcp = false;
    const CanonMove& m = reader.move();
    if (tcp && reader.moved() && m.from_known() && m.to_known())
      out.push_back({m.from, m.to, m.a_from, m.a_to, m.c_from, m.c_to, i + 1});
  }
  return out;
}

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double len2 = d.squaredNorm();
  const double f = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + f * d)).norm();
}

}  // namespace

TEST(LinuxcncXyzac, AFiveAxisFinishKeepsTheTipOnItsCutterLocationsAllAlongTheRun) {
  // A dome of radius 9 standing on the table (its plate's bottom at the table's top), finished in five axes with
  // the simulator's tool 5 as a ball of 6 mm; the program switches to tool-centre-point kinematics itself.
  const Mesh dome = test_parts::dome_on_plate(9, 11, 3, 72, 24);
  std::vector<Vec3> corners;
  for (size_t f = 0; f < dome.face_count(); ++f)
    for (int i = 0; i < 3; ++i) corners.push_back(dome.corner(f, i) + Vec3(0, 0, 3));
  const Mesh part = build_mesh(corners);
  PlanParams p;
  p.tool.id = 5;
  p.tool.cutter = Cutter::ball(6);
  p.tool.feed = 900;
  p.tool.plunge_feed = 300;
  p.stepover = 4.5;
  p.tolerance = 0.005;
  p.tool_axis.cone_deg = 40;
  const Job job = five_axis_finish(part, p, {});
  const gcode::MachineLimits limits =
      gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine_xyzac_tcp.yaml");
  gcode::PostOptions o = gcode::with_tool_centre_point({}, limits, "test");
  o.work_offset = gcode::WorkOffset{};
  o.work_offset_note = "the table's centre";
  gcode::ProgramChecks checks;
  checks.machine = limits;
  checks.limits.stock_top = part.bbox.max.z();
  checks.rs274 = true;
  const std::vector<std::string> program = gcode::prepare_program(job, o, checks).program.lines;
  const std::vector<TipSegment> moves = tool_centre_point_moves(program);
  ASSERT_GT(moves.size(), 100u);
  const double estimate = gcode::estimate_cycle_time(program, limits.trajectory).seconds;

  REQUIRE_MACHINE_SIMULATOR(sim, "xyzac");
  auto c = sim.controller();
  c->connect();
  // The controller's position while the program runs: in tool-centre-point kinematics its world X Y Z are the tip
  // on the table that its own kinematics (xyzac-trt-kins) computes from the joints.
  struct Sample {
    Vec3 tip;
    double a, c;
    size_t line;
  };
  std::vector<Sample> samples;
  // Its world Z holds the tool's length besides (LinuxCNC's trtfuncs.c takes the length out of the joints before it
  // turns them and adds it back to Z): the tip is that far below.
  const Vec3 length(0, 0, sim.tool_length(5));
  const size_t first_line = moves.front().line, last_line = moves.back().line;
  const auto run = sim.run_timed(*c, program, 2.0, [&](const ControllerStatus& s) {
    // Not at the last move's line: the controller goes on reporting it while M429 switches the kinematics back,
    // after which its world coordinates are the joints'.
    if (s.position_known && s.rotary_known && s.current_line > first_line && s.current_line < last_line)
      samples.push_back({s.position - length, s.a, s.c, s.current_line});
  });
  c->disconnect();
  ASSERT_GT(samples.size(), 50u) << "too few positions read during the run";
  double worst = 0, worst_axis = 0;
  for (const Sample& smp : samples) {
    // The nearest of the program's segments around the line the controller reports (it reads ahead a little).
    double best = INFINITY, best_axis = INFINITY;
    for (const TipSegment& m : moves) {
      if (m.line + 40 < smp.line || m.line > smp.line + 40) continue;
      const double d = distance_to_segment(smp.tip, m.from, m.to);
      if (d < best) {
        best = d;
        // Where along the move, the axis the controller's A and C point the tool along against the one there.
        const Vec3 seg = m.to - m.from;
        const double f =
            seg.squaredNorm() > 0 ? std::clamp((smp.tip - m.from).dot(seg) / seg.squaredNorm(), 0.0, 1.0) : 0.0;
        const Vec3 planned =
            limits.trunnion->tool_axis(m.a_from + f * (m.a_to - m.a_from), m.c_from + f * (m.c_to - m.c_from));
        best_axis =
            std::acos(std::clamp(limits.trunnion->tool_axis(smp.a, smp.c).dot(planned), -1.0, 1.0)) * 180 / M_PI;
      }
    }
    worst = std::max(worst, best);
    if (std::isfinite(best_axis)) worst_axis = std::max(worst_axis, best_axis);
  }
  EXPECT_LT(worst, 0.01) << "over " << samples.size() << " positions read during the run";
  RecordProperty("samples", static_cast<int>(samples.size()));
  std::printf(
      "five-axis run: %zu positions read, the tip at most %.4f mm off the program's moves, the axis at most "
      "%.3f degrees off; estimated %.1f s, the simulator %.1f s (%+.1f %%)\n",
      samples.size(), worst, worst_axis, estimate, run.all, 100 * (estimate - run.all) / run.all);
  EXPECT_LT(std::abs(estimate - run.all), 0.10 * run.all) << "estimate " << estimate << " s, simulator " << run.all;
}
