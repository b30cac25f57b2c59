// The one program pipeline (gcode/prepare_program.hpp) and the one judge of a running program
// (control/program_run.hpp): a job that breaks a machine limit is refused naming the line and the limit, by the
// core and by every command that writes G-code (`plan -o prog.ngc` included); a run fails on a controller gone
// idle or silent, and a feed hold is not a stall.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <mutex>

#include "cli_run.hpp"
#include "rosmill/control/program_run.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"
#include "test_post_jobs.hpp"

using namespace rosmill::core;
namespace fs = std::filesystem;

namespace {

gcode::MachineLimits small_machine() {
  gcode::MachineLimits m;
  m.name = "small";
  m.envelope.add(Vec3(-20, -20, -30));
  m.envelope.add(Vec3(20, 20, 50));
  m.table_z = -25;
  m.max_feed = 5000;
  m.max_spindle_rpm = 24000;
  return m;
}

TEST(ProgramPipeline, RefusesAJobOutsideTheEnvelopeNamingTheLine) {
  const Job job{test::raster_toolpath(40, 30)};  // x reaches 40 mm: outside the small machine's 20
  gcode::ProgramChecks checks;
  checks.machine = small_machine();
  try {
    gcode::prepare_program(job, {}, checks);
    FAIL() << "a program outside the envelope was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("line "), std::string::npos) << what;
    EXPECT_NE(what.find("envelope x max"), std::string::npos) << what;
  }
  // Inside the envelope it passes, marked as checked; without a machine (an explicit opt-out) it is not checked.
  const Job inside{test::raster_toolpath(10, 10)};
  EXPECT_TRUE(gcode::prepare_program(inside, {}, checks).limits_checked);
  EXPECT_FALSE(gcode::prepare_program(job, {}, gcode::ProgramChecks{}).limits_checked);
}

TEST(ProgramPipeline, Rs274ComparesTheProgramWithTheJob) {
  gcode::ProgramChecks checks;
  checks.rs274 = true;
  const gcode::PreparedProgram p = gcode::prepare_program(Job{test::cylinder_contours()}, {}, checks);
  ASSERT_TRUE(p.rs274.has_value());
  EXPECT_TRUE(p.rs274->ok);
  EXPECT_EQ(p.rs274->toolpath_moves, test::cylinder_contours().move_count());
  EXPECT_LE(p.rs274->max_deviation, 0.001);
  EXPECT_THROW(gcode::prepare_program(Job{}, {}, checks), Error);
  EXPECT_THROW(gcode::check_program({}, checks, "empty.ngc"), Error);
}

TEST(RunMonitor, EndStatesAndStalls) {
  using control::ControllerStatus;
  using control::RunState;
  using control::RunVerdict;
  const auto t0 = control::RunMonitor::Clock::now();
  const auto at = [&](double s) { return t0 + std::chrono::milliseconds(int(s * 1000)); };
  control::RunMonitor m(5.0);
  ControllerStatus s;
  s.state = RunState::Running;
  s.current_line = 3;
  EXPECT_EQ(m.observe(s, at(0)), RunVerdict::Going);
  EXPECT_EQ(m.observe(s, at(4.9)), RunVerdict::Going);
  s.state = RunState::Paused;  // a feed hold: the operator's pause, however long, is not a stall
  EXPECT_EQ(m.observe(s, at(20)), RunVerdict::Going);
  s.state = RunState::Running;
  EXPECT_EQ(m.observe(s, at(24)), RunVerdict::Going);
  ControllerStatus stalled = s;
  EXPECT_EQ(m.observe(stalled, at(28.9)), RunVerdict::Going);
  EXPECT_EQ(m.observe(stalled, at(29.1)), RunVerdict::Failed);
  EXPECT_NE(stalled.error.find("no progress for"), std::string::npos) << stalled.error;
  EXPECT_NE(stalled.error.find("line 3"), std::string::npos) << stalled.error;

  control::RunMonitor idle_monitor(5.0);
  ControllerStatus idle;
  idle.state = RunState::Idle;  // a controller that dropped the program before its end
  EXPECT_EQ(idle_monitor.observe(idle, at(0)), RunVerdict::Failed);
  EXPECT_EQ(idle.error, "the controller went idle");
  ControllerStatus alarm;
  alarm.state = RunState::Alarm;
  alarm.error = "ALARM:2";
  EXPECT_EQ(idle_monitor.observe(alarm, at(0)), RunVerdict::Failed);
  EXPECT_EQ(alarm.error, "ALARM:2");  // the controller's own words are kept
  ControllerStatus done;
  done.state = RunState::Finished;
  EXPECT_EQ(idle_monitor.observe(done, at(100)), RunVerdict::Finished);
}

// A file controller runs a program at once: ProgramRun reports it finished from its worker.
TEST(ProgramRun, RunsToTheEndOnItsWorker) {
  char tmpl[] = "/tmp/rosmill-run-XXXXXX";
  ASSERT_NE(::mkdtemp(tmpl), nullptr);
  const std::string dir = tmpl;
  std::vector<control::RunVerdict> verdicts;
  std::mutex m;
  {
    control::ProgramRun run(control::open_controller("file://" + dir), {"G21 G90", "G0 Z5", "M2"}, {}, 5.0,
                            [&](const control::ControllerStatus&, control::RunVerdict v) {
                              std::lock_guard<std::mutex> lock(m);
                              verdicts.push_back(v);
                            });
    run.join();
    EXPECT_FALSE(run.active());
    EXPECT_THROW(run.abort(), Error);  // nothing runs any more
  }
  ASSERT_FALSE(verdicts.empty());
  EXPECT_EQ(verdicts.back(), control::RunVerdict::Finished);
  EXPECT_TRUE(fs::exists(dir + "/rosmill.ngc"));
  fs::remove_all(dir);
}

// `rosmill plan -o prog.ngc` goes through the same checks as `post` and `send`: a machine too small for the part
// refuses the program and nothing is written; --no-limits is the explicit way round.
TEST(ProgramPipelineCli, PlanToGcodeIsCheckedAgainstTheMachine) {
  char tmpl[] = "/tmp/rosmill-plan-limits-XXXXXX";
  ASSERT_NE(::mkdtemp(tmpl), nullptr);
  const std::string dir = tmpl;
  ASSERT_EQ(run_rosmill_in(dir, "primitive cube -o cube.stl").status, 0);  // 60 mm cube
  std::ofstream(dir + "/small.yaml") << "name: small\nenvelope: {x: [-20, 20], y: [-20, 20], z: [-60, 100]}\n"
                                        "table_z: -55\nmax_feed: 5000\nmax_spindle_rpm: 24000\n"
                                        "clearance_over_stock: 2\n";
  const std::string plan = "plan cube.stl --strategy contour --tool flat:6@5 --stepdown 20 ";
  CliRun r = run_rosmill_in(dir, plan + "--machine small.yaml -o refused.ngc 2>&1");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("line "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("envelope"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir + "/refused.ngc"));

  r = run_rosmill_in(dir, plan + "--machine missing.yaml -o x.ngc 2>&1");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("no machine file 'missing.yaml'"), std::string::npos) << r.out;

  EXPECT_EQ(run_rosmill_in(dir, plan + "--no-limits -o free.ngc").status, 0);
  EXPECT_TRUE(fs::exists(dir + "/free.ngc"));
  // From a folder without config/, the package's machine is found and checked (the cube fits in it).
  EXPECT_EQ(run_rosmill_in(dir, plan + "-o fits.ngc").status, 0);
  EXPECT_TRUE(fs::exists(dir + "/fits.ngc"));
  fs::remove_all(dir);
}

}  // namespace

namespace {

// The highest cutter location of the feed moves in a toolpath file.
double top_feed_z(const std::string& path) {
  double top = -1e300;
  for (const Toolpath& tp : read_toolpath_file(path))
    for (const ToolpathPass& pass : tp.passes)
      for (const Move& m : pass.moves)
        if (m.type == MoveType::Feed) top = std::max(top, m.to.z());
  return top;
}

// `rosmill plan --setup`: the part is turned so that the setup's tool axis points up. The seed cylinder (r 25,
// h 60 on z = 0) seen from +Z has its top at 60; from +X its side at x = 25 becomes the top.
TEST(PlanSetupCli, TheToolpathIsPlannedOnThePartTurnedForTheSetup) {
  char tmpl[] = "/tmp/rosmill-plan-setup-XXXXXX";
  ASSERT_NE(::mkdtemp(tmpl), nullptr);
  const std::string dir = tmpl;
  ASSERT_EQ(run_rosmill_in(dir, "primitive cylinder -o cyl.stl").status, 0);
  const std::string plan = "plan cyl.stl --strategy raster --tool flat:10 --stepover 8 --json ";
  CliRun r = run_rosmill_in(dir, plan + "-o z.json");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("\"name\":\"+Z\""), std::string::npos) << r.out;
  EXPECT_NEAR(top_feed_z(dir + "/z.json"), 60.0, 1e-6);
  r = run_rosmill_in(dir, plan + "--setup +x -o x.json");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("\"name\":\"+X\""), std::string::npos) << r.out;
  EXPECT_NEAR(top_feed_z(dir + "/x.json"), 25.0, 0.05);
  r = run_rosmill_in(dir, plan + "--setup 1,0,0 -o d.json");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NEAR(top_feed_z(dir + "/d.json"), 25.0, 0.05);
  r = run_rosmill_in(dir, plan + "--setup +W 2>&1");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("--setup"), std::string::npos) << r.out;
  r = run_rosmill_in(dir, plan + "--setup 0,0,0 2>&1");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("finite non-zero"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

}  // namespace
