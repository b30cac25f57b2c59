// The work offset a registered part sets (G10 L2 P1): from the workpiece's pose, written by the post in each
// dialect, followed by the machine-limit check in machine coordinates, accepted by LinuxCNC's own interpreter
// (rs274) with the toolpath's moves unchanged, carried by a resume, and given to the CLI as numbers or as a
// registration's JSON.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>

#include "cli_run.hpp"
#include "error_of.hpp"
#include "rosmill/control/controller.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/gcode/rs274_check.hpp"
#include "rosmill/gcode/work_offset.hpp"
#include "test_post_jobs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::gcode;

namespace {

Eigen::Matrix4d pose(double rz_deg, double tilt_deg, const Vec3& at) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.topLeftCorner<3, 3>() = (Eigen::AngleAxisd(rz_deg * M_PI / 180, Vec3::UnitZ()) *
                             Eigen::AngleAxisd(tilt_deg * M_PI / 180, Vec3::UnitX()))
                                .toRotationMatrix();
  t.topRightCorner<3, 1>() = at;
  return t;
}

MachineLimits bundled_machine() { return load_machine_limits(ROSMILL_SOURCE_DIR "/config/machine.yaml"); }

size_t line_of(const Program& p, const std::string& prefix) {
  for (size_t i = 0; i < p.lines.size(); ++i)
    if (p.lines[i].rfind(prefix, 0) == 0) return i;
  return p.lines.size();
}

}  // namespace

TEST(WorkOffset, FromAPoseItsOriginAndTurnAboutZ) {
  const WorkOffset w = work_offset_of_pose(pose(30, 0, Vec3(120, -40, -35)), 0.05, "pose");
  EXPECT_NEAR(w.origin.x(), 120, 1e-12);
  EXPECT_NEAR(w.origin.y(), -40, 1e-12);
  EXPECT_NEAR(w.origin.z(), -35, 1e-12);
  EXPECT_NEAR(w.rotation_deg, 30, 1e-12);
  // A program point goes where the pose puts the part's point, and back.
  const Vec3 p(10, 5, 2);
  const Vec3 expected = (pose(30, 0, Vec3(120, -40, -35)) * p.homogeneous()).head<3>();
  EXPECT_LT((w.to_machine(p) - expected).norm(), 1e-12);
  EXPECT_LT((w.to_program(w.to_machine(p)) - p).norm(), 1e-12);
  EXPECT_NEAR(work_offset_of_pose(pose(-170, 0, Vec3::Zero()), 0.05, "pose").rotation_deg, -170, 1e-9);
  // Within the tilt allowed; beyond it refused with the angle.
  EXPECT_NO_THROW(work_offset_of_pose(pose(10, 0.04, Vec3::Zero()), 0.05, "pose"));
  const std::string tilted = error_of([] { work_offset_of_pose(pose(10, 1.5, Vec3::Zero()), 0.05, "pose"); });
  EXPECT_NE(tilted.find("pose: the workpiece is tilted 1.5 degrees"), std::string::npos) << tilted;
  Eigen::Matrix4d scaled = pose(0, 0, Vec3::Zero());
  scaled(0, 0) = 2;
  EXPECT_FALSE(error_of([&] { work_offset_of_pose(scaled, 0.05, "pose"); }).empty());
}

TEST(WorkOffset, ParsedFromNumbers) {
  const WorkOffset w = parse_work_offset("100, -20.5,-30,12.5", "--work-offset");
  EXPECT_EQ(w.origin, Vec3(100, -20.5, -30));
  EXPECT_EQ(w.rotation_deg, 12.5);
  EXPECT_EQ(parse_work_offset("1,2,3", "x").rotation_deg, 0);
  for (const char* bad : {"", "1,2", "1,2,3,", "1,2,3,4,5", "1,x,3", "1,2,nan", "1,2,3e999", "1,,3"})
    EXPECT_EQ(error_of([&] { parse_work_offset(bad, "--work-offset"); }).rfind("--work-offset: ", 0), 0u)
        << bad;
}

TEST(WorkOffset, ThePostSetsG54BeforeTheFirstMove) {
  const Job job{test::raster_toolpath()};
  PostOptions o;
  o.work_offset = WorkOffset{Vec3(100, -20, -30), 12.5};
  const Program p = post(job, o);
  const size_t g10 = line_of(p, "G10 L2 P1");
  ASSERT_LT(g10, p.lines.size());
  EXPECT_EQ(p.lines[g10], "G10 L2 P1 X100 Y-20 Z-30 R12.5");
  EXPECT_LT(g10, line_of(p, "G0"));
  EXPECT_LT(g10, line_of(p, "G17"));  // G54 selected after its data is set
  // GRBL has no R: square to the axes it is written without; turned it is refused, not rounded away.
  o.dialect = "grbl";
  const std::string turned = error_of([&] { post(job, o); });
  EXPECT_NE(turned.find("grbl has no coordinate system rotation"), std::string::npos) << turned;
  o.work_offset->rotation_deg = 0;
  const Program g = post(job, o);
  EXPECT_EQ(g.lines[line_of(g, "G10")], "G10 L2 P1 X100 Y-20 Z-30");
}

TEST(WorkOffset, TheLimitCheckFollowsItInMachineCoordinates) {
  const MachineLimits m = bundled_machine();  // envelope x, y [-254, 254], z [-50.8, 101.6]; table z -50
  const std::vector<std::string> body = {"G17 G21 G90 G54", "G0 Z10", "X0 Y0", "S10000 M3", "G1 Z-5 F100",
                                         "X200", "G0 Z10", "M30"};
  EXPECT_TRUE(check_limits(body, m).empty());
  auto with = [&](const std::string& g10) {
    std::vector<std::string> l = body;
    l.insert(l.begin(), g10);
    return check_limits(l, m);
  };
  EXPECT_TRUE(with("G10 L2 P1 X50 Y0 Z0").empty());
  // Shifted 60 mm in X the cut ends at machine x 260, past the soft limit.
  auto v = with("G10 L2 P1 X60 Y0 Z0");
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v.front().limit, "envelope x max");
  EXPECT_NE(v.front().detail.find("machine x 260"), std::string::npos) << v.front().detail;
  // Turned 90 degrees the same cut runs along machine +Y: x stays in, y 200 + 60 leaves.
  v = with("G10 L2 P1 X60 Y60 Z0 R90");
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v.front().limit, "envelope y max");
  EXPECT_TRUE(with("G10 L2 P1 X60 Y0 Z0 R90").empty());
  // Lowered, the plunge goes below the table.
  v = with("G10 L2 P1 X0 Y0 Z-45.5");
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v.front().limit, "table");
  // Another coordinate system set and not selected leaves G54's moves as they are.
  EXPECT_TRUE(with("G10 L2 P2 X60 Y0 Z0").empty());
  // What the check cannot follow stays refused: L20, axes left out, P beyond the six systems.
  for (const char* g10 : {"G10 L20 P1 X0 Y0 Z0", "G10 L2 P1 X0 Y0", "G10 P1 X0 Y0 Z0", "G10 L2 P7 X0 Y0 Z0"}) {
    v = with(g10);
    ASSERT_FALSE(v.empty()) << g10;
    EXPECT_EQ(v.front().limit, "unchecked move") << g10;
  }
}

// A job's setups each set and select their own system (G55..G59): the check follows the one selected, and refuses
// one selected before the program gave its origin.
TEST(WorkOffset, EachSetupsSystemIsFollowed) {
  const MachineLimits m = bundled_machine();
  const std::vector<std::string> cut = {"G0 Z10", "X0 Y0", "S10000 M3", "G1 Z-5 F100", "X200", "G0 Z10", "M30"};
  auto program = [&](std::vector<std::string> head) {
    head.insert(head.end(), cut.begin(), cut.end());
    return head;
  };
  EXPECT_TRUE(check_limits(program({"G10 L2 P3 X50 Y0 Z0", "G17 G21 G90 G56"}), m).empty());
  auto v = check_limits(program({"G10 L2 P3 X60 Y0 Z0", "G17 G21 G90 G56"}), m);
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v.front().limit, "envelope x max");
  // G54's origin is the machine file's; G56 set far away does not move G54's cut.
  EXPECT_TRUE(check_limits(program({"G10 L2 P3 X600 Y0 Z0", "G17 G21 G90 G54"}), m).empty());
  v = check_limits(program({"G17 G21 G90 G57"}), m);
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v.front().limit, "work offset");
  EXPECT_NE(v.front().detail.find("G57 selected before the program set its origin"), std::string::npos)
      << v.front().detail;
  // P0 sets the active system.
  EXPECT_TRUE(check_limits(program({"G10 L2 P4 X0 Y0 Z0", "G57", "G10 L2 P0 X50 Y0 Z0"}), m).empty());
  v = check_limits(program({"G10 L2 P4 X0 Y0 Z0", "G57", "G10 L2 P0 X60 Y0 Z0"}), m);
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v.front().limit, "envelope x max");
}

TEST(WorkOffset, ThePostSelectsTheSetupsSystem) {
  const Job job{test::raster_toolpath()};
  PostOptions o;
  o.work_offset = WorkOffset{Vec3(10, -20, -30), 0, 3};
  o.work_offset_note = "at setup 3's datum";
  const Program p = post(job, o);
  const size_t g10 = line_of(p, "G10 L2 P3");
  ASSERT_LT(g10, p.lines.size());
  EXPECT_EQ(p.lines[g10], "G10 L2 P3 X10 Y-20 Z-30 R0");
  EXPECT_EQ(p.lines[g10 - 1], "(work offset G56 at setup 3's datum)");
  const size_t setup = line_of(p, "G17");
  ASSERT_LT(setup, p.lines.size());
  EXPECT_NE(p.lines[setup].find("G56"), std::string::npos) << p.lines[setup];
  EXPECT_EQ(p.lines[setup].find("G54"), std::string::npos) << p.lines[setup];
  const Rs274Result r = run_rs274(p.lines);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(compare_with_job(p, job, r, o.arc_tolerance).ok);
  EXPECT_TRUE(check_limits(p.lines, bundled_machine()).empty());
  o.work_offset->index = 7;
  EXPECT_NE(error_of([&] { post(job, o); }).find("P7 is not one of P1..P6"), std::string::npos);
}

TEST(WorkOffset, Rs274AcceptsItAndTheMovesStayTheToolpaths) {
  const Job job{test::raster_toolpath(), test::cylinder_contours()};
  PostOptions o;
  o.arcs = true;
  o.work_offset = WorkOffset{Vec3(-80, 35, -20), -7.25};
  const Program p = post(job, o);
  const Rs274Result r = run_rs274(p.lines);
  ASSERT_TRUE(r.ok) << r.error;
  const VerifyReport rep = compare_with_job(p, job, r, o.arc_tolerance);
  EXPECT_TRUE(rep.ok) << rep.problem;
  EXPECT_LE(rep.max_deviation, o.arc_tolerance + 0.001);
}

TEST(WorkOffset, AResumeSetsItAgain) {
  PostOptions o;
  o.work_offset = WorkOffset{Vec3(10, 20, -30), 5};
  const Program p = post(Job{test::raster_toolpath()}, o);
  control::SendOptions send;
  send.from_line = p.lines.size() - 4;
  const auto pre = control::resume_preamble(p.lines, send, "linuxcnc");
  ASSERT_GE(pre.size(), 2u);
  EXPECT_EQ(pre[1], "G10 L2 P1 X10 Y20 Z-30 R5");
}

TEST(WorkOffset, TheCliTakesNumbersOrARegistration) {
  const std::string dir = ::testing::TempDir() + "/work_offset_cli";
  std::filesystem::create_directories(dir);
  const std::string toolpath = dir + "/raster.json";
  ASSERT_EQ(run_rosmill("primitive cube -o " + dir + "/cube.stl").status, 0);
  ASSERT_EQ(run_rosmill("plan " + dir + "/cube.stl --strategy raster --tool flat:6@5 -o " + toolpath).status, 0);
  const CliRun numbers =
      run_rosmill("post " + toolpath + " -o " + dir + "/a.ngc --work-offset 10,20,-20,3");
  ASSERT_EQ(numbers.status, 0) << numbers.err;
  std::ifstream a(dir + "/a.ngc");
  const std::string text((std::istreambuf_iterator<char>(a)), {});
  EXPECT_NE(text.find("\nG10 L2 P1 X10 Y20 Z-20 R3\n"), std::string::npos);
  // A registration: the design turned 90 degrees and moved; the pose's tilt beyond the allowance is refused.
  auto registration = [&](const Eigen::Matrix4d& t, bool ambiguous) {
    const std::string path = dir + "/registration.json";
    std::ofstream out(path);
    out << "{\"transform\": [";
    for (int r = 0; r < 4; ++r)
      out << (r ? "," : "") << "[" << t(r, 0) << "," << t(r, 1) << "," << t(r, 2) << "," << t(r, 3) << "]";
    out << "], \"rms\": 0.01, \"ambiguous\": " << (ambiguous ? "true, \"ambiguity\": \"a cube\"" : "false") << "}";
    return path;
  };
  const CliRun reg = run_rosmill("post " + toolpath + " -o " + dir + "/b.ngc --work-offset " +
                                            registration(pose(90, 0, Vec3(5, 6, -25)), false));
  ASSERT_EQ(reg.status, 0) << reg.err;
  std::ifstream b(dir + "/b.ngc");
  const std::string btext((std::istreambuf_iterator<char>(b)), {});
  EXPECT_NE(btext.find("\nG10 L2 P1 X5 Y6 Z-25 R90\n"), std::string::npos);
  const CliRun tilted = run_rosmill("post " + toolpath + " -o " + dir + "/c.ngc --work-offset " +
                                               registration(pose(0, 2, Vec3::Zero()), false));
  EXPECT_NE(tilted.status, 0);
  EXPECT_NE(tilted.err.find("tilted 2 degrees"), std::string::npos) << tilted.err;
  const CliRun ambiguous = run_rosmill("post " + toolpath + " -o " + dir + "/d.ngc --work-offset " +
                                                  registration(pose(0, 0, Vec3::Zero()), true));
  EXPECT_NE(ambiguous.status, 0);
  EXPECT_NE(ambiguous.err.find("ambiguous (a cube)"), std::string::npos) << ambiguous.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/c.ngc") || std::filesystem::exists(dir + "/d.ngc"));
}
