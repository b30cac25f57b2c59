// The LinuxCNC driver against the REAL LinuxCNC (package linuxcnc-uspace): the stock sim/axis_mm machine, started
// headless by scripts/linuxcnc-sim for each test and stopped by PID when the test ends (also when it fails; a
// watchdog stops it if the test process is killed). Programs come from the post-processor; positions are the
// controller's own (ABS_ACT_POS). Every wait is bounded: a test fails, it never hangs.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>

#include "rosmill/control/controller.hpp"
#include "rosmill/control/program_run.hpp"
#include "rosmill/control/linuxcnc.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/gcode/post.hpp"
#include "linuxcnc_simulator.hpp"
#include "test_post_jobs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::control;

using sim_test::Simulator;
using sim_test::slurp;

namespace {

using Clock = std::chrono::steady_clock;

// A job sized for the simulator's speeds (30 mm/s: a few seconds): a zig-zag `width` wide and a circle that the
// post writes as an arc, with tool 1 of the simulator's table.
Job small_job(double width, int zigzag_lines) {
  Toolpath raster = test::raster_toolpath(width, 3.0 * (zigzag_lines - 1), 3, -1, 1);
  Toolpath circle = test::revolution_contours("circle", [](double) { return 2.0; }, 2, 2, 72, 1);
  for (Toolpath* tp : {&raster, &circle}) {
    tp->tool.feed = 1500;
    tp->tool.plunge_feed = 600;
    for (ToolpathPass& pass : tp->passes)
      for (Move& m : pass.moves)
        if (m.type != MoveType::Rapid) m.feed = m.type == MoveType::Feed ? 1500 : 600;
  }
  return {raster, circle};
}

std::vector<std::string> posted(const Job& job) {
  gcode::PostOptions o;
  o.arcs = true;
  o.arc_tolerance = 0.01;
  return gcode::post(job, o).lines;
}

// Where the program leaves the tool tip, in program coordinates (the G54 offset of the simulator is zero).
Vec3 last_point(const std::vector<std::string>& program) {
  return gcode::state_before(program, program.size()).position;
}

// Polls until `done` holds; false after `seconds`.
bool poll_until(Controller& c, double seconds, const std::function<bool(const ControllerStatus&)>& done,
                ControllerStatus* last = nullptr) {
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) {
    const ControllerStatus s = c.poll(0.05);
    if (last) *last = s;
    if (done(s)) return true;
  }
  return false;
}

// The position once the machine has come to rest (two polls 0.2 s apart agree), waiting at most `seconds`: a
// deceleration takes longer on a loaded machine, so the test waits for it instead of sleeping a fixed time.
ControllerStatus settled(Controller& c, double seconds = 10.0) {
  ControllerStatus before = c.poll(0.05);
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    const ControllerStatus now = c.poll(0.05);
    if (now.position_known && before.position_known && (now.position - before.position).norm() < 1e-6) return now;
    before = now;
  }
  ADD_FAILURE() << "the machine did not come to rest within " << seconds << " s";
  return before;
}

void expect_at(const ControllerStatus& s, const Vec3& expected, const std::string& what) {
  ASSERT_TRUE(s.position_known) << what;
  EXPECT_LT((s.position - expected).cwiseAbs().maxCoeff(), 0.002)
      << what << ": machine at " << s.position.transpose() << ", expected " << expected.transpose();
}

}  // namespace

TEST(LinuxcncSimulator, RunsAPostedProgramToItsLastPointAndReportsAnError) {
  REQUIRE_SIMULATOR(sim);
  auto c = sim.controller();
  c->connect();  // handshake, enable, estop off, machine on, home
  const std::vector<std::string> program = posted(small_job(10, 2));
  size_t last_line = 0;
  bool lines_in_order = true, seen_running = false;
  const ControllerStatus s = run_to_end(
      *c, program, SendOptions{},
      [&](const ControllerStatus& st) {
        seen_running |= st.state == RunState::Running;
        if (st.current_line == 0) return;
        lines_in_order &= st.current_line >= last_line && st.current_line <= program.size();
        last_line = st.current_line;
      },
      60.0);
  EXPECT_EQ(s.state, RunState::Finished);
  EXPECT_TRUE(seen_running);
  EXPECT_TRUE(lines_in_order) << "the executing line went backwards";
  EXPECT_GT(last_line, program.size() / 2) << "status never showed the program's lines";
  EXPECT_EQ(s.acknowledged_line, program.size());
  // The machine ends where the program's last move goes; G43 adds the tool's length to machine Z.
  expect_at(s, last_point(program) + Vec3(0, 0, sim.tool_length(1)), "after the program");

  // An interpreter error (G1 without a feed) stops the program; the driver reports LinuxCNC's message and how far
  // it got, and claims no line past the error as done.
  const std::vector<std::string> bad = {"G17 G21 G90 G54", "G0 Z5", "G0 X2 Y1", "G1 X5", "G0 Z10", "M30"};
  try {
    run_to_end(*c, bad, SendOptions{}, {}, 30.0);
    ADD_FAILURE() << "the program with an error ran to its end";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("Cannot do g1 with zero feed rate"), std::string::npos) << what;
    EXPECT_NE(what.find("program line"), std::string::npos) << what;
    EXPECT_NE(what.find("--from-line"), std::string::npos) << what;
  }
  const ControllerStatus after = c->poll(0.05);
  EXPECT_EQ(after.state, RunState::Error);
  EXPECT_LE(after.acknowledged_line, 3u);
  c->disconnect();
}

TEST(LinuxcncSimulator, FeedHoldResumeAbortThenResumeFromTheLine) {
  REQUIRE_SIMULATOR(sim);
  auto c = sim.controller();
  c->connect();
  const std::vector<std::string> program = posted(small_job(24, 6));
  c->start(program, SendOptions{});
  ControllerStatus s;
  // Into the cutting moves (below z 0 in program coordinates, so machine z < tool length).
  const double tip = sim.tool_length(1);
  ASSERT_TRUE(poll_until(*c, 30, [&](const ControllerStatus& st) {
    return st.state == RunState::Running && st.position_known && st.position.z() < tip - 0.5;
  }, &s)) << "never reached the cut: " << run_state_name(s.state) << " " << s.error;

  // Feed hold: the machine stops and stays.
  c->feed_hold();
  ASSERT_TRUE(poll_until(*c, 5, [](const ControllerStatus& st) { return st.state == RunState::Paused; }, &s));
  const Vec3 held = settled(*c).position;
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  s = c->poll(0.05);
  EXPECT_EQ(s.state, RunState::Paused);
  EXPECT_LT((s.position - held).norm(), 1e-6) << "the machine moved during the feed hold";

  // Resume: it moves on.
  c->resume();
  ASSERT_TRUE(poll_until(*c, 5, [&](const ControllerStatus& st) {
    return st.state == RunState::Running && (st.position - held).norm() > 0.5;
  }, &s)) << "no motion after resume: " << run_state_name(s.state);

  // Abort: the program stops where it is, short of its end.
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  c->abort();
  const ControllerStatus aborted = settled(*c);
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  s = c->poll(0.05);
  EXPECT_EQ(s.state, RunState::Idle);
  EXPECT_LT((s.position - aborted.position).norm(), 1e-6) << "the machine moved after the abort";
  EXPECT_EQ(c->get("program_status"), "IDLE");
  ASSERT_GT(aborted.acknowledged_line, 0u);
  ASSERT_LT(aborted.acknowledged_line, program.size());

  // Resume from the first line not done: the preamble restores the modal state (tool, offset, spindle, feed) and
  // goes to where that line starts; the program then ends at its last point.
  SendOptions from;
  from.from_line = aborted.acknowledged_line + 1;
  const ControllerStatus done = run_to_end(*c, program, from, {}, 60.0);
  EXPECT_EQ(done.state, RunState::Finished);
  EXPECT_EQ(done.acknowledged_line, program.size());
  expect_at(done, last_point(program) + Vec3(0, 0, tip), "after resuming from line " + std::to_string(from.from_line));
  c->disconnect();
}
