// 3+2 on a trunnion table (XYZAC, LinuxCNC's xyzac-trt): the machine file's kinematics, the A and C that bring each
// setup's tool axis under the spindle (known answers, and the rotation itself checked by its own formula), the least
// rotary motion between setups, -Z refused, the rotary ranges and simultaneous moves refused by the checker with
// their line, the post's indexing blocks, and the two-sided example job: one program, one clamping, the part turned
// by A, checked by an independent sweep of its toolpaths mapped back through frames this test builds from the
// machine's chain, by the program read back and simulated through its rotary moves, and by LinuxCNC's rs274. A part
// that would turn into the spindle while the table indexes is refused, naming the indexing block.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>

#include "error_of.hpp"
#include "job_test_options.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/cycle_time.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/gcode/rs274_check.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/job/run_job.hpp"
#include "rosmill/machine/trunnion.hpp"
#include "rosmill/setups/reach.hpp"
#include "rosmill/testing/sanitized.hpp"
#include "rosmill/testing/swept_check.hpp"
#include "test_post_jobs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::job;

namespace {

const std::string kMachine = std::string(ROSMILL_SOURCE_DIR) + "/config/machine_xyzac.yaml";

const gcode::MachineLimits& xyzac() {
  static const gcode::MachineLimits m = gcode::load_machine_limits(kMachine);
  return m;
}

const machine::Trunnion& trunnion() { return *xyzac().trunnion; }

// The turn of the table at (a, c) written out from the chain, not from machine/trunnion.cpp: C about the table's Z,
// then A about machine X.
Eigen::Matrix3d turn(double a, double c) {
  const double ra = a * M_PI / 180, rc = c * M_PI / 180;
  Eigen::Matrix3d rx, rz;
  rx << 1, 0, 0, 0, std::cos(ra), -std::sin(ra), 0, std::sin(ra), std::cos(ra);
  rz << std::cos(rc), -std::sin(rc), 0, std::sin(rc), std::cos(rc), 0, 0, 0, 1;
  return rx * rz;
}

std::vector<std::string> check(const std::string& program) {
  std::vector<std::string> lines;
  std::istringstream in(program);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::vector<std::string> found;
  gcode::LimitCheckOptions checked_by_stock;  // as the job checks them: its rapids were swept through the stock
  checked_by_stock.rapids_checked_by_stock = true;
  for (const gcode::LimitViolation& v : gcode::check_limits(lines, xyzac(), checked_by_stock))
    found.push_back("line " + std::to_string(v.line) + " " + v.limit + ": " + v.detail);
  return found;
}

bool any_contains(const std::vector<std::string>& v, const std::string& what) {
  for (const std::string& s : v)
    if (s.find(what) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(Trunnion, MachineFileGivesTheSimulatorsChain) {
  const machine::Trunnion& t = trunnion();
  EXPECT_EQ(t.a.min, -100.0);
  EXPECT_EQ(t.a.max, 50.0);
  EXPECT_EQ(t.c.min, -36000.0);
  EXPECT_EQ(t.c.max, 36000.0);
  EXPECT_EQ(t.pivot, Vec3(0, 20, 10));
  EXPECT_EQ(t.mode, machine::KinematicsMode::Identity);
  EXPECT_EQ(t.safe_z, 110.0);
  // The chain: a table point p at (a, c) is R_x(a) (R_z(c) p - pivot) + pivot (the C axis through machine zero).
  for (const double a : {0.0, -90.0, 33.0})
    for (const double c : {0.0, 90.0, -217.5}) {
      const Vec3 p(12.5, -7, 31);
      const Vec3 expected = turn(a, 0) * (turn(0, c) * p - t.pivot) + t.pivot;
      EXPECT_LT((t.machine_point(p, a, c) - expected).norm(), 1e-9) << a << " " << c;
      EXPECT_LT((t.table_point(t.machine_point(p, a, c), a, c) - p).norm(), 1e-9);
      const Placement at = t.table_in_machine(a, c);
      EXPECT_LT((at.point(p) - expected).norm(), 1e-9);
    }
}

TEST(Trunnion, MachineFileFieldsAreChecked) {
  std::ifstream in(kMachine);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(error_of([&] { gcode::parse_machine_limits(text, "m.yaml"); }), "");
  auto refused = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const size_t at = t.find(from);
    if (at == std::string::npos) return "'" + from + "' is not in the machine file";
    t.replace(at, from.size(), to);
    return error_of([&] { gcode::parse_machine_limits(t, "m.yaml"); });
  };
  EXPECT_NE(refused("trunnion-ac", "head-bc").find("rotary.kinematics: must be trunnion-ac"), std::string::npos);
  EXPECT_NE(refused("[-100, 50]", "[50, -100]").find("rotary.a.range: min must be below max"), std::string::npos);
  EXPECT_NE(refused("[-100, 50], velocity: 30, ", "[-100, 50], ").find("velocity"),
            std::string::npos);
  EXPECT_NE(refused("safe_z: 110", "safe_z: 130").find("rotary.safe_z: must lie in [-120, 120], got 130"),
            std::string::npos);
  EXPECT_NE(refused("max_tool_length: 30", "").find("rotary.max_tool_length: missing"), std::string::npos);
  EXPECT_NE(refused("safe_z: 110", "safe_z: 110\n  spin: 3").find("rotary.spin: unknown field"), std::string::npos);
  EXPECT_NE(refused("a_pivot: [0, 20, 10]", "a_pivot: [0, 20]").find("rotary.a_pivot"), std::string::npos);
  EXPECT_NE(
      refused("5: 30, 6: 30", "5: 40, 6: 30").find("tool 5's length offset 40 mm is over rotary.max_tool_length 30"),
      std::string::npos);
}

// The known answers on this machine (A from -100 to 50 degrees): +Z at A 0; the sides at A -90 with C turning the
// side's normal onto machine -Y first; -Z needs A = 180 and is refused.
TEST(Trunnion, IndexingKnownAnswers) {
  const machine::Trunnion& t = trunnion();
  struct Case {
    Vec3 d;
    double a, c;
  };
  const Case cases[] = {{Vec3::UnitZ(), 0, 0},    {-Vec3::UnitY(), -90, 0}, {Vec3::UnitX(), -90, -90},
                        {-Vec3::UnitX(), -90, 90}, {Vec3::UnitY(), -90, 180}};
  for (const Case& k : cases) {
    const auto i = machine::index_for(t, k.d, machine::Index{});
    ASSERT_TRUE(i) << k.d.transpose();
    EXPECT_NEAR(i->a, k.a, 1e-9) << k.d.transpose();
    EXPECT_NEAR(std::remainder(i->c - k.c, 360.0), 0.0, 1e-9) << k.d.transpose() << ": C " << i->c;
    // The rotation itself: the tool axis of the table is machine +Z at that turn.
    EXPECT_LT((turn(i->a, i->c) * k.d - Vec3::UnitZ()).norm(), 1e-12) << k.d.transpose();
  }
  std::string why;
  EXPECT_FALSE(machine::index_for(t, -Vec3::UnitZ(), machine::Index{}, &why));
  EXPECT_NE(why.find("A = 180"), std::string::npos) << why;
  EXPECT_NE(why.find("outside A's range [-100, 50]"), std::string::npos) << why;
  // A tilted axis has two solutions (A and -A); here only the one inside A's range.
  const Vec3 tilted = Vec3(0, -1, 1).normalized();
  const auto i = machine::index_for(t, tilted, machine::Index{});
  ASSERT_TRUE(i);
  EXPECT_LT((turn(i->a, i->c) * tilted - Vec3::UnitZ()).norm(), 1e-12);
  EXPECT_NEAR(i->a, -45, 1e-9);
}

// Least rotary motion: C goes round by the nearest whole turn, and of A's two solutions the nearer wins when both
// lie in range.
TEST(Trunnion, IndexingTakesTheLeastRotaryMotion) {
  const machine::Trunnion& t = trunnion();
  const auto from_350 = machine::index_for(t, -Vec3::UnitY(), machine::Index{-90, 350});
  ASSERT_TRUE(from_350);
  EXPECT_NEAR(from_350->c, 360.0, 1e-9);
  const auto to_y = machine::index_for(t, Vec3::UnitY(), machine::Index{-90, -170});
  ASSERT_TRUE(to_y);
  EXPECT_NEAR(to_y->c, -180.0, 1e-9);
  // With A's range opened to +-100, +X at A +90 (C 90) is nearer to A 80 than A -90 (C -90).
  machine::Trunnion wide = t;
  wide.a.max = 100;
  const auto near = machine::index_for(wide, Vec3::UnitX(), machine::Index{80, 90});
  ASSERT_TRUE(near);
  EXPECT_NEAR(near->a, 90.0, 1e-9);
  EXPECT_NEAR(near->c, 90.0, 1e-9);
  EXPECT_LT((turn(near->a, near->c) * Vec3::UnitX() - Vec3::UnitZ()).norm(), 1e-12);
  // +Z keeps C where it is.
  const auto top = machine::index_for(t, Vec3::UnitZ(), machine::Index{-90, 725});
  ASSERT_TRUE(top);
  EXPECT_NEAR(top->a, 0.0, 1e-9);
  EXPECT_NEAR(top->c, 725.0, 1e-9);
}

// The checker: A and C are machine limits like the envelope, a move that turns them while X, Y or Z move is refused
// (a 3+2 program indexes with A and C alone), the G53 retract is followed in machine coordinates, and on a machine
// without rotary axes any A or C is refused.
TEST(Trunnion, CheckerRefusesRotaryRangesAndSimultaneousMovesWithTheirLine) {
  const std::string head = "G21 G90 G17\nG54\nT5 M6\nG43 H5\nS10000 M3\n";
  EXPECT_TRUE(check(head + "G53 G0 Z110\nG0 A-90 C0\nG0 X0 Y20 Z60\nG1 Z50 F500\nG0 Z60\nM30\n").empty());
  EXPECT_TRUE(any_contains(check(head + "G53 G0 Z110\nG0 A-101 C0\nM30\n"), "line 7 rotary a min"));
  EXPECT_TRUE(any_contains(check(head + "G53 G0 Z110\nG0 A0 C36001\nM30\n"), "line 7 rotary c max"));
  EXPECT_TRUE(any_contains(check(head + "G0 A0 C0\nG0 X0 Y0 Z60\nG1 X10 A-10 F500\nM30\n"),
                           "line 8 simultaneous move"));
  EXPECT_TRUE(any_contains(check(head + "G53 G0 Z121\nM30\n"), "line 6 envelope z max"));
  gcode::MachineLimits three = gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine.yaml");
  std::vector<std::string> lines = {"G21 G90", "G0 X0 Y0 Z10", "G0 A10"};
  const auto v = gcode::check_limits(lines, three);
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v[0].line, 3u);
  EXPECT_EQ(v[0].limit, "rotary axes");
}

// The post: between toolpaths at another turn, the tool up in machine coordinates, then A and C alone.
TEST(Trunnion, PostIndexesWithAG53RetractThenAAndC) {
  Toolpath a;
  a.strategy = "top";
  a.tool = job_test::package_tools().get(5);
  a.clearance_z = 50;
  a.start = Vec3(0, 0, 50);
  a.indexed = true;
  a.passes.push_back(test::pass_of({test::move_to(MoveType::Feed, Vec3(0, 0, 40), 500), test::move_to(MoveType::Feed, Vec3(10, 0, 40), 500)}));
  Toolpath b = a;
  b.strategy = "side";
  b.a = -90;
  b.c = 180;
  // Over the tilted table: 20 mm above its top at A -90 (machine Y 30 is table Z 20 there).
  b.start = Vec3(0, 30, 60);
  b.clearance_z = 60;
  b.passes = {test::pass_of({test::move_to(MoveType::Feed, Vec3(0, 30, 52), 500),
                             test::move_to(MoveType::Feed, Vec3(10, 30, 52), 500)})};
  gcode::PostOptions o;
  o.index_safe_z = 110;
  const gcode::Program p = gcode::post({a, b}, o);
  std::vector<size_t> retracts, indexes;
  for (size_t k = 0; k < p.lines.size(); ++k) {
    if (p.lines[k].find("G53 G0 Z110") != std::string::npos) retracts.push_back(k);
    if (p.lines[k].find("G0 A") == 0 || p.lines[k].find(" G0 A") != std::string::npos) indexes.push_back(k);
  }
  ASSERT_EQ(retracts.size(), 2u);
  ASSERT_EQ(indexes.size(), 2u);
  // Between the retract and the turn only the tool change (the first toolpath's tool is loaded up there), and
  // right after the turn the way over the toolpath's start at that height.
  for (int k = 0; k < 2; ++k) {
    ASSERT_GT(indexes[k], retracts[k]);
    for (size_t l = retracts[k] + 1; l < indexes[k]; ++l)
      EXPECT_TRUE(p.lines[l].rfind("T", 0) == 0 || p.lines[l].rfind("G43", 0) == 0 || p.lines[l].rfind("M", 0) == 0)
          << p.lines[l];
    EXPECT_EQ(p.lines[indexes[k] + 1].rfind("G0 X", 0), 0u) << p.lines[indexes[k] + 1];
  }
  EXPECT_NE(p.lines[indexes[0]].find("G0 A0 C0"), std::string::npos) << p.lines[indexes[0]];
  EXPECT_NE(p.lines[indexes[1]].find("G0 A-90 C180"), std::string::npos) << p.lines[indexes[1]];
  // Through the whole program pipeline: the machine's limits (A, C, the turned table) and LinuxCNC's rs274 reading
  // the program back move by move against the toolpaths (the G53 retract is rs274's own traverse).
  gcode::ProgramChecks checks;
  checks.machine = xyzac();
  checks.rs274 = true;
  EXPECT_EQ(error_of([&] { gcode::prepare_program({a, b}, o, checks); }), "");
  // The same toolpaths without a safe Z are refused, not posted without their retract.
  EXPECT_NE(error_of([&] { gcode::post({a, b}, gcode::PostOptions{}); }).find("index_safe_z"), std::string::npos);
}

// The example job: the slotted block, its top at A 0 and its -Y side at A -90, one program, one vise.
TEST(Trunnion, TwoSidedJobOneProgramNoGougeAndFacesMachined) {
  const std::string dir = job_test::scratch("trunnion_slotted");
  const JobSpec spec = read_job(std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/slotted_block_xyzac.yaml");
  swept_check::SweptJob swept;
  std::optional<Placement> on_table;
  JobOptions o = job_test::options(dir, "machine_xyzac.yaml");
  o.operation_done = [&](const OperationView& v) {
    // The setup's frame built here from the chain and the A and C the job chose (the job's own frame unused).
    ASSERT_TRUE(v.setup.index);
    SetupFrame f;
    f.name = v.setup.name;
    Placement table{"machine", "table", Eigen::Isometry3d::Identity()};
    table.pose.linear() = turn(v.setup.index->a, v.setup.index->c);
    const Vec3 pv = trunnion().pivot;
    table.pose.translation() = turn(v.setup.index->a, 0) * (-pv) + pv;
    f.placement = compose(table, *on_table, "test");
    swept.add(f, v.toolpaths);
  };
  // Where the job stands the workpiece on the table (centred over the machine's fixture position, on the vise):
  // from a run without programs.
  const JobReport probe = run_job(spec, job_test::options("", "machine_xyzac.yaml"));
  ASSERT_TRUE(probe.workpiece_on_table);
  on_table = probe.workpiece_on_table;
  EXPECT_TRUE(probe.indexed);
  const JobReport r = run_job(spec, o);
  ASSERT_EQ(r.setups.size(), 2u);
  ASSERT_TRUE(r.setups[0].index && r.setups[1].index);
  EXPECT_EQ(r.setups[0].index->a, 0.0);
  EXPECT_NEAR(r.setups[1].index->a, -90.0, 1e-9);
  EXPECT_NEAR(std::remainder(r.setups[1].index->c, 360.0), 0.0, 1e-9);
  EXPECT_GT(r.setups[1].indexing_s, 90.0 / 30.0);  // A turns 90 degrees at 30 degrees/s at least
  // One program for both setups, accepted by rs274, with the indexing blocks in it.
  EXPECT_EQ(r.setups[0].program, r.setups[1].program);
  ASSERT_FALSE(r.setups[0].program.empty());
  size_t programs = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) programs += e.path().extension() == ".ngc";
  EXPECT_EQ(programs, 1u);
  const std::vector<std::string> lines = gcode::read_program_lines(r.setups[0].program);
  const gcode::Rs274Result rs = gcode::run_rs274(lines);
  EXPECT_TRUE(rs.ok) << "line " << rs.error_line << ": " << rs.error;
  size_t turns = 0;
  for (const std::string& l : lines) turns += l.rfind("G0 A", 0) == 0 || l.find(" G0 A") != std::string::npos;
  EXPECT_EQ(turns, 2u);
  // The job's time (its operations' moves and each turn's retract, turn and way down, once) against the written
  // program's estimate, which test_linuxcnc_xyzac checks against the simulator: 389.1 s against 395.6 s (the
  // simulator ran it in 393.0 s). Each operation timed with its own indexing as well had made it 433.7 s.
  const double program_s = gcode::estimate_cycle_time(lines, xyzac().trajectory).seconds;
  EXPECT_NEAR(r.time_s, program_s, 0.03 * program_s) << "the job says " << r.time_s << " s";
  gcode::LimitCheckOptions checked_by_stock;  // as the job checks them: its rapids were swept through the stock
  checked_by_stock.rapids_checked_by_stock = true;
  for (const gcode::LimitViolation& v : gcode::check_limits(lines, xyzac(), checked_by_stock))
    ADD_FAILURE() << "line " << v.line << " " << v.limit << ": " << v.detail;
  // The stock model and the verifier: no gouge, and what is left is the part; the program read back and simulated
  // through its rotary moves agrees.
  EXPECT_GE(r.min_left_mm, -0.001);
  EXPECT_EQ(r.gouge_mm, 0.0);
  ASSERT_TRUE(r.program_check.done);
  EXPECT_EQ(r.program_check.runs, 2u);
  EXPECT_EQ(r.program_check.gouge_mm, 0.0);
  const double design = 54400;
  EXPECT_NEAR(r.left_mm3 - design, r.program_check.left_mm3, 0.02 * design);
  // Every face either setup reaches: the sweep of the toolpaths leaves no more than the tolerance on it (the
  // bottom stands on the vise floor; the ends in the jaws and the +Y face face away from both setups).
  const Mesh part = read_stl(std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/data/slotted_block.stl");
  // The vise's boxes in the workpiece frame (the first setup is A 0, C 0: the machine frame is the table's); the
  // cutter keeps 1 mm off them, so a face within its radius and that clearance of a box is the fixture's to hide.
  std::vector<Box3> fixture;
  for (const fixture::FixtureBox& b : r.setups[0].fixture.boxes)
    fixture.push_back(Box3::between(b.box.min - on_table->translation(), b.box.max - on_table->translation()));
  const auto hidden = [&](const Vec3& p) {
    for (const Box3& b : fixture)
      if ((p - p.cwiseMax(b.min).cwiseMin(b.max)).norm() < 3.0 + 1.0 + 0.5) return true;
    return false;
  };
  const setups::SurfaceSamples samples = setups::sample_surface(part, 0.7);
  size_t checked = 0, left = 0, gouges = 0, shadowed = 0, slivers = 0;
  for (size_t k = 0; k < samples.size(); k += rosmill::testing::kReferenceStride) {
    const Vec3& n = samples.normals[k];
    if (n.z() < -0.999 || std::abs(n.x()) > 0.999 || n.y() > 0.999) continue;
    if (hidden(samples.points[k])) {
      ++shadowed;
      continue;
    }
    ++checked;
    // The allowance (0) and 0.3 mm: the raster's samples are 0.75 mm apart along its lines, and its straight move
    // from the floor up a wall's foot cuts the corner: a sliver at most 0.2 mm wide beside the wall is left there
    // (counted apart: the surface is reached within 0.2 mm sideways).
    const Vec3 q = samples.points[k] + 0.31 * n;
    if (swept.swept(q)) continue;
    const Vec3 u = n.cross(std::abs(n.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitX()).normalized(), v = n.cross(u);
    if (swept.swept(q + 0.2 * u) || swept.swept(q - 0.2 * u) || swept.swept(q + 0.2 * v) || swept.swept(q - 0.2 * v)) {
      ++slivers;
      continue;
    }
    if (++left <= 10)
      ADD_FAILURE() << "material left over " << samples.points[k].transpose() << " (normal " << n.transpose() << ")";
  }
  EXPECT_GT(checked * rosmill::testing::kReferenceStride, 5000u);
  EXPECT_LT(shadowed, checked / 4) << "the vise hides a quarter of the faces";
  EXPECT_LT(slivers * 100, checked) << "wall-foot slivers on more than 1 % of the faces";
  EXPECT_EQ(left, 0u);
  for (size_t k = 0; k < samples.size(); k += 5 * rosmill::testing::kReferenceStride)
    if (swept.swept(samples.points[k] - 0.005 * samples.normals[k])) ++gouges;
  EXPECT_EQ(gouges, 0u);
  std::filesystem::remove_all(dir);
}

// A part that stands too tall for the table to turn under the retracted tool: the indexing is refused, naming the
// indexing block and the setup, and no program is written.
TEST(Trunnion, PartTurningIntoTheSpindleIsRefusedNamingTheBlock) {
  const std::string dir = job_test::scratch("trunnion_tall");
  // The cube (60 mm) in a 70 x 70 x 65 mm stock on a vise floor 5 mm up: its top (70 mm) clears the tool's tip at
  // A 0 (110 - 30 - 2 = 78 mm), but its corner 35 mm in front of the A axis comes up to 91 mm as the table tilts.
  const JobSpec spec = parse_job(
      "part: primitive:cube\nstock: {box: {margin: 5}}\n"
      "fixture: {vise: {jaw_width: 60, jaw_height: 5, grip: 5, opening: 200, floor: 5, clamp: x}}\nsetups:\n"
      "  - {direction: +Z, operations: [{strategy: rough, tool: 5, stepover: 5, stepdown: 20}]}\n"
      "  - {direction: -Y, operations: [{strategy: rough, tool: 5, stepover: 5, stepdown: 20}]}\n",
      "tall.yaml", dir);
  const std::string e = error_of([&] { run_job(spec, job_test::options(dir + "/out", "machine_xyzac.yaml")); });
  EXPECT_NE(e.find("the indexing block G0 A-90 C0"), std::string::npos) << e;
  EXPECT_NE(e.find("setups[1]"), std::string::npos) << e;
  EXPECT_NE(e.find("spindle"), std::string::npos) << e;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  // -Z cannot be reached on this machine: refused with the reason.
  const JobSpec under = parse_job(
      "part: primitive:cube\nsetups:\n  - {direction: -Z, operations: [{strategy: rough, tool: 5}]}\n", "under.yaml",
      dir);
  const std::string z = error_of([&] { run_job(under, job_test::options("", "machine_xyzac.yaml")); });
  EXPECT_NE(z.find("this machine cannot index the part for it"), std::string::npos) << z;
  EXPECT_NE(z.find("A = 180"), std::string::npos) << z;
  std::filesystem::remove_all(dir);
}

// A 40 x 30 x 25 mm block with a pocket on top, a slot in -Y, a blind hole in +X and a step at -X, setups chosen,
// in the small vise on the trunnion: the +X setup's waterline once closed a contour of the vise, which runs off its
// grid, with a chord through the part (a 13.5 mm gouge the verifier refused). Now no operation cuts into the part,
// the 3+2 program read back and simulated through its indexings finds no gouge, and on the 3-axis mill the same
// job's figures are over the whole surface (the slot's sharp corners keep the end mill out, its full depth).
TEST(Trunnion, ChosenSetupsOnTheTrunnionPlanNoGouge) {
  const std::string dir = job_test::scratch("trunnion_block");
  const std::string job =
      "part: " ROSMILL_TEST_DATA "/parts/trunnion_block.stl\nstock: {box: {margin: 0}}\ndatum: workpiece\n"
      "held_face: -Z\nsetups: auto\naccept_unfinished: true\n"
      "fixture: {vise: {jaw_width: 40, jaw_height: 12, jaw_thickness: 10, opening: 60, grip: 4, floor: 10, clamp: x}}\n"
      "operations:\n"
      "  - {name: rough, strategy: rough, tool: 5, stepover: 2.4, stepdown: 2, allowance: 0.3}\n"
      "  - {name: walls, strategy: waterline, tool: 5, stepdown: 0.5}\n"
      "  - {name: floors, strategy: raster, tool: 5, stepover: 2}\n";
  const JobSpec spec = parse_job(job, "block.yaml", dir);
  const JobReport r = run_job(spec, job_test::options(dir, "machine_xyzac.yaml"));
  EXPECT_TRUE(r.indexed);
  EXPECT_GE(r.setups.size(), 3u);
  EXPECT_EQ(r.gouge_mm, 0.0);
  ASSERT_TRUE(r.program_check.done);
  EXPECT_EQ(r.program_check.gouge_mm, 0.0);
  EXPECT_GE(r.surface.min_left_mm, -0.01);
  const JobReport mill = run_job(spec, job_test::options());
  EXPECT_EQ(mill.gouge_mm, 0.0);
  EXPECT_EQ(mill.max_left_mm, mill.surface.max_left_mm);
  EXPECT_NEAR(mill.max_left_mm, 8.0, 0.01);  // the slot's corner, 8 mm deep
  std::filesystem::remove_all(dir);
}

TEST(Trunnion, TheSameJobOnTheToolCentrePointMachineSelectsIdentityKinematicsFirst) {
  // config/machine_xyzac_tcp.yaml is the same simulator with tool-centre-point control: a 3+2 job there is the
  // identity machine's, its program the same but for M429 before the first turn (a five-axis program run before it
  // leaves LinuxCNC in M428). Before, the job was refused on that machine file.
  const JobSpec spec = read_job(std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/slotted_block_xyzac.yaml");
  const std::string id_dir = job_test::scratch("trunnion_identity"), tcp_dir = job_test::scratch("trunnion_tcp");
  const JobReport id = run_job(spec, job_test::options(id_dir, "machine_xyzac.yaml"));
  const JobReport tcp = run_job(spec, job_test::options(tcp_dir, "machine_xyzac_tcp.yaml"));
  ASSERT_TRUE(tcp.indexed);
  EXPECT_EQ(tcp.surface.min_left_mm, id.surface.min_left_mm);
  EXPECT_EQ(tcp.surface.max_left_mm, id.surface.max_left_mm);
  EXPECT_EQ(tcp.time_s, id.time_s);
  ASSERT_TRUE(tcp.program_check.done);
  EXPECT_EQ(tcp.program_check.gouge_mm, 0.0);
  std::vector<std::string> a = gcode::read_program_lines(id.setups[0].program);
  const std::vector<std::string> b = gcode::read_program_lines(tcp.setups[0].program);
  const auto first_turn =
      std::find_if(a.begin(), a.end(), [](const std::string& l) { return l.rfind("G53 G0 Z", 0) == 0; });
  ASSERT_NE(first_turn, a.end());
  a.insert(a.insert(first_turn - 1, "M429"), "(identity kinematics: the program's X Y Z are the machine's axes)");
  EXPECT_EQ(a, b);
  EXPECT_TRUE(gcode::run_rs274(b).ok);
  // A five-axis operation in a job is refused, naming it, on either machine.
  JobSpec five = spec;
  five.operations.back().strategy = "five-axis";
  five.operations.back().tool = "2";  // the 6 mm ball
  for (const char* machine : {"machine_xyzac.yaml", "machine_xyzac_tcp.yaml"}) {
    const std::string e = error_of([&] { run_job(five, job_test::options("", machine)); });
    EXPECT_NE(e.find("(" + five.operations.back().name + ")"), std::string::npos) << e;
    EXPECT_NE(e.find("tool axis at every move"), std::string::npos) << e;
  }
}
