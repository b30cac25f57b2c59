// Jobs of several setups: the stock carried from setup to setup (a later roughing cuts only what is left, an
// operation with nothing left plans no move), each setup's own work offset checked in machine coordinates, the
// fixture kept clear of and a path into it refused with the move, and the pocket casting machined top and sides:
// every face some setup reaches within the allowance and the tolerance of the design, checked by an independent
// sweep of every setup's toolpaths mapped back through its frame (swept_check.hpp), the stock model and the
// verifier agreeing, and every program accepted by LinuxCNC's rs274.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <set>

#include "error_of.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/gcode/rs274_check.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/job/run_job.hpp"
#include "rosmill/segment/surface_patches.hpp"
#include "rosmill/setups/reach.hpp"
#include "rosmill/testing/sanitized.hpp"
#include "job_test_options.hpp"
#include "rosmill/testing/swept_check.hpp"

using namespace rosmill::core;
using namespace rosmill::core::job;
using job_test::options;
using job_test::package_tools;

namespace {

void expect_rs274_accepts(const std::string& program) {
  const gcode::Rs274Result r = gcode::run_rs274(gcode::read_program_lines(program));
  EXPECT_TRUE(r.ok) << program << " line " << r.error_line << ": " << r.error;
  EXPECT_GT(r.moves.size(), 5u) << program;
}

}  // namespace

// The cube roughed from +Z, then from -X (the part turned over onto its +X face), then from -X again. The second
// roughing cuts what the first left there and little air (the bound: a fifth of its feed path); the third has
// nothing left to cut and plans no move. Each setup's program sets its own work offset, which the default machine
// accepts (with one offset for both, the -X roughing would reach 10 mm below the table).
TEST(JobSetups, CubeFromTheTopThenTheSideCutsOnlyWhatIsLeft) {
  const std::string dir = job_test::scratch("job_setups_cube");
  const JobSpec spec = parse_job(
      "part: primitive:cube\nstock: {box: {margin: 5}}\noperations:\n"
      "  - {name: top, strategy: rough, tool: 1, stepover: 4, stepdown: 2.5, allowance: 0.5}\n"
      "  - {name: side, strategy: rough, tool: 1, stepover: 4, stepdown: 2.5, allowance: 0.5, setup: -X}\n"
      "  - {name: again, strategy: rough, tool: 1, stepover: 4, stepdown: 2.5, allowance: 0.5, setup: -X}\n",
      "cube.yaml", dir);
  const JobReport r = run_job(spec, options(dir));
  ASSERT_EQ(r.operations.size(), 3u);
  ASSERT_EQ(r.setups.size(), 2u);
  EXPECT_EQ(r.setups[0].face_down, "-Z");
  EXPECT_EQ(r.setups[1].face_down, "+X");
  ASSERT_TRUE(r.setups[0].work_offset && r.setups[1].work_offset);
  EXPECT_EQ(r.setups[0].work_offset->code(), "G54");
  EXPECT_EQ(r.setups[1].work_offset->code(), "G55");
  // Each datum is the stock's top centre as the setup sees it: the stock stands on the table (z -50) there.
  EXPECT_NEAR(r.setups[0].work_offset->origin.z(), -50 + 65, 1e-9);
  EXPECT_NEAR(r.setups[1].work_offset->origin.z(), -50 + 70, 1e-9);
  EXPECT_GT(r.operations[1].removed_mm3, 1000.0);
  EXPECT_LT(r.operations[1].air_cut_share, 0.2);
  EXPECT_EQ(r.operations[2].moves, 0u);
  EXPECT_EQ(r.operations[2].cutting_mm, 0.0);
  EXPECT_EQ(r.operations[2].removed_mm3, 0.0);
  EXPECT_NEAR(r.removed_mm3, r.stock_mm3 - r.left_mm3, 1e-6 * r.stock_mm3);
  EXPECT_GE(r.min_left_mm, -0.001);
  EXPECT_EQ(r.gouge_mm, 0.0);
  // Two programs, one a setup, each setting its own offset before its first move; LinuxCNC accepts both.
  ASSERT_FALSE(r.setups[1].program.empty());
  EXPECT_NE(r.setups[0].program, r.setups[1].program);
  const std::vector<std::string> side = gcode::read_program_lines(r.setups[1].program);
  EXPECT_NE(std::find(side.begin(), side.end(), "G10 L2 P2 X0 Y0 Z20 R0"), side.end());
  for (const SetupReport& s : r.setups) expect_rs274_accepts(s.program);
  // The machine's limits through each offset: on a machine whose Z travel ends 10 mm over the table's stock, the
  // programs' safe heights are refused, naming the setup and the limit; nothing is written.
  JobOptions low = options(dir + "/low");
  low.checks.machine->envelope.max.z() = 10;
  const std::string refused = error_of([&] { run_job(spec, low); });
  EXPECT_NE(refused.find("setup 1 (+Z) program"), std::string::npos) << refused;
  EXPECT_NE(refused.find("envelope z max"), std::string::npos) << refused;
  EXPECT_FALSE(std::filesystem::exists(dir + "/low"));
  std::filesystem::remove_all(dir);
}

// A side setup held in a vise whose jaws stand 65 mm up the stock (90 mm high from -X, 15 mm over the cube all
// round): the roughing keeps its cutter off the jaws, and at its deepest levels beside them its holder (32 mm
// across, 40 mm above the tip) too: those levels stop a holder's reach short of the jaws, where the stock stays
// (the fixture check, which refuses a move into a jaw, has nothing to refuse). With the jaws gripping 5 mm the
// same job cuts deeper there.
TEST(JobSetups, TheHolderKeepsOffAHighJawAndLowerJawsLetItDeeper) {
  const std::string job =
      "part: primitive:cube\nstock: {box: {margin: 15}}\nsetups:\n"
      "  - direction: -X\n"
      "    fixture: {vise: {jaw_width: 100, jaw_height: JAW, grip: GRIP, clamp: y}}\n"
      "    operations:\n"
      "      - {name: rough, strategy: rough, tool: 1, stepover: 4, stepdown: 2.5, allowance: 0.5}\n";
  auto with = [&](const std::string& jaw, const std::string& grip) {
    std::string text = job;
    text.replace(text.find("JAW"), 3, jaw);
    text.replace(text.find("GRIP"), 4, grip);
    return parse_job(text, "vise.yaml", ROSMILL_SOURCE_DIR);
  };
  const JobReport high = run_job(with("70", "65"), options());
  const JobReport low = run_job(with("25", "5"), options());
  ASSERT_EQ(high.operations.size(), 1u);
  ASSERT_EQ(low.operations.size(), 1u);
  EXPECT_GT(high.operations[0].moves, 0u);
  EXPECT_EQ(high.gouge_mm, 0.0);
  EXPECT_EQ(low.gouge_mm, 0.0);
  // The high jaws' top stands 25 mm under the stock's top: below 65 mm down the holder would meet them beside the
  // stock, so that much of the 15 mm margin stays.
  EXPECT_LT(high.operations[0].removed_mm3, low.operations[0].removed_mm3);
}

// The example job: the pocket part from its casting, top and four sides, each in a vise, the bottom held.
TEST(JobSetups, PocketCastingMachinedTopAndSides) {
  const std::string dir = job_test::scratch("job_setups_pocket");
  const std::string file = std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/pocket_sides.yaml";
  const JobSpec spec = read_job(file);
  swept_check::SweptJob swept;
  JobOptions o = options(dir);
  o.operation_done = [&](const OperationView& v) { swept.add(v.setup.frame, v.toolpaths); };
  const JobReport r = run_job(spec, o);
  ASSERT_EQ(r.setups.size(), 5u);
  const Mesh part = read_stl(std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/data/pocket.stl");
  // The stock model and the verifier agree: no gouge either way, and what is left is the part.
  EXPECT_GE(r.min_left_mm, -0.001);
  EXPECT_EQ(r.gouge_mm, 0.0);
  EXPECT_NEAR(r.left_mm3, 36447.4, 0.01 * 36447.4);
  // Only the bottom, which the part stands on, is not machined.
  EXPECT_NEAR(r.unreachable_area, 50.0 * 40.0, 1e-6);
  std::set<std::string> offsets;
  for (const SetupReport& s : r.setups) {
    ASSERT_TRUE(s.work_offset) << s.name;
    offsets.insert(s.work_offset->code());
    EXPECT_GT(s.finished_area, 0.0) << s.name;
    expect_rs274_accepts(s.program);
  }
  EXPECT_EQ(offsets.size(), 5u);
  // Every face some setup reaches: the stock left no more than the allowance (0) and the tolerance (1 um) on it,
  // with 5 um for the search's own step: a point that far outside the part lies in some setup's swept cutter.
  const setups::SurfaceSamples samples = setups::sample_surface(part, 0.7);
  size_t checked = 0, left = 0;
  for (size_t k = 0; k < samples.size(); k += rosmill::testing::kReferenceStride) {
    if (samples.normals[k].z() < -0.999) continue;  // the bottom, held
    ++checked;
    if (!swept.swept(samples.points[k] + 0.006 * samples.normals[k])) {
      ++left;
      ADD_FAILURE() << "material left over " << samples.points[k].transpose() << " (normal "
                    << samples.normals[k].transpose() << ")";
      if (left > 10) break;
    }
  }
  EXPECT_GT(checked * rosmill::testing::kReferenceStride, 10000u);  // every 16th sample under the sanitizers
  EXPECT_EQ(left, 0u);
  // No setup's toolpaths, mapped back through its frame, reach into the part deeper than 5 um.
  std::mt19937 random(3);
  size_t gouges = 0;
  for (size_t k = 0; k < samples.size(); k += 7 * rosmill::testing::kReferenceStride)
    if (swept.swept(samples.points[k] - 0.005 * samples.normals[k])) ++gouges;
  EXPECT_EQ(gouges, 0u);
  std::filesystem::remove_all(dir);
}

TEST(JobSetups, FieldsAreCheckedWithTheirLine) {
  auto error = [](const std::string& text) {
    return error_of([&] { parse_job("part: primitive:cube\n" + text, "job.yaml", ROSMILL_SOURCE_DIR); });
  };
  const std::string ops = "    operations: [{strategy: rough, tool: flat:10@1}]\n";
  EXPECT_EQ(error("setups:\n  - direction: -X\n" + ops), "");
  EXPECT_EQ(error("setups:\n  - direction: [1, 1, 0]\n" + ops), "");
  EXPECT_NE(error("setups:\n  - direction: -W\n" + ops).find("job.yaml:3 setups[0].direction: expected +Z"),
            std::string::npos);
  EXPECT_NE(error("setups:\n  - direction: [0, 0, 0]\n" + ops).find("must not be zero"), std::string::npos);
  EXPECT_NE(error("setups:\n  - {operations: [{strategy: rough, tool: flat:10@1}]}\n").find("direction: missing"),
            std::string::npos);
  EXPECT_NE(error("setups:\n  - direction: +Z\n").find("setups[0].operations: missing"), std::string::npos);
  EXPECT_NE(error("setups:\n  - direction: +Z\n    operations: [{strategy: rough, tool: flat:10@1, setup: -X}]\n")
                .find("setups[0].operations[0].setup: an operation of a job with setups runs in its setup"),
            std::string::npos);
  EXPECT_NE(error("setups:\n  - direction: +Z\n" + ops + "operations: [{strategy: rough, tool: flat:10@1}]\n")
                .find("a job with setups gives each setup its operations"),
            std::string::npos);
  EXPECT_NE(error("setups:\n  - direction: +Z\n    datum: middle\n" + ops).find("setups[0].datum: expected top-centre"),
            std::string::npos);
  EXPECT_NE(error("setups:\n  - direction: +Z\n    fixture: {vise: {grip: -1}}\n" + ops)
                .find("job.yaml:4 setups[0].fixture.vise.grip: must lie in"),
            std::string::npos);
  EXPECT_NE(error("setups:\n  - direction: +Z\n    fixture: {vise: {clamp: z}}\n" + ops).find("must be x or y"),
            std::string::npos);
  EXPECT_NE(error("setups:\n  - direction: +Z\n    fixture: {vice: {}}\n" + ops).find("unknown field"),
            std::string::npos);
  EXPECT_NE(error("setups:\n  - direction: +Z\n    fixture: {boxes: [{min: [0, 0, 0], max: [1, 1, -1]}]}\n" + ops)
                .find("must lie above min"),
            std::string::npos);
  EXPECT_NE(error("held_face: -Z\noperations: [{strategy: rough, tool: flat:10@1}]\n").find("held_face: only a job with setups"),
            std::string::npos);
  std::string seven = "setups:\n";
  for (int k = 0; k < 7; ++k) seven += "  - direction: +Z\n" + ops;
  EXPECT_NE(error(seven).find("7 setups, more than the six work offsets"), std::string::npos);
  // A vise too narrow for the stock is refused when the setup begins, naming it.
  const JobSpec narrow = parse_job("part: primitive:cube\nsetups:\n  - direction: -X\n    fixture: {vise: {opening: 50}}\n" + ops,
                                   "job.yaml", ROSMILL_SOURCE_DIR);
  const std::string wide = error_of([&] { run_job(narrow, options()); });
  EXPECT_NE(wide.find("job.yaml:3 setups[0] (-X) fixture.vise: the stock is 70 mm across the jaws"), std::string::npos)
      << wide;
}

// A bar 180 mm long, too long to stand on its end under the default machine's spindle: with `setups: auto` neither
// end is a setup (the tip clearing the stock would rise above the Z travel). The blind hole in its +X end only an end
// setup reaches, so the job is refused before anything is planned, naming the setups and why; a job that accepts
// faces left unfinished runs the rest, and reports the hole as machined by no setup for the machine.
TEST(JobSetups, ALongBarIsNotStoodOnItsEnd) {
  const std::string dir = job_test::scratch("job_setups_long_bar");
  const std::string job = "part: " ROSMILL_TEST_DATA "/parts/long_bar.stl\nstock: {box: {margin: 3}}\n"
                          "setups: auto\nheld_face: -Z\nfixture: {vise: {opening: 200, clamp: y}}\n"
                          "operations: [{name: rough, strategy: rough, tool: 1, stepover: 4, stepdown: 5, "
                          "allowance: 0.5}]\n";
  const std::string refused = error_of([&] { run_job(parse_job(job, "bar.yaml", dir), options()); });
  EXPECT_NE(refused.find("bar.yaml setups: "), std::string::npos) << refused;
  EXPECT_NE(refused.find("reached only by setups that do not fit the machine"), std::string::npos) << refused;
  EXPECT_NE(refused.find("+X: the stock stands 186.0 mm high in it"), std::string::npos) << refused;
  EXPECT_NE(refused.find("above linuxcnc-sim-mm's Z travel (101.6)"), std::string::npos) << refused;
  const JobReport r = run_job(parse_job(job + "accept_unfinished: true\n", "bar.yaml", dir), options());
  for (const SetupReport& s : r.setups) EXPECT_LT(std::abs(s.direction.x()), 0.5) << s.name;
  double machine = 0;
  for (const setups::Unreached& u : r.unreachable)
    if (u.reason == "machine") machine += u.area;
  // The hole's floor and wall: pi 4^2 + 10 x the 32-gon's perimeter of 8 mm across.
  EXPECT_NEAR(machine, 16 * M_PI + 10 * 32 * 8 * std::sin(M_PI / 32), 6.0);
  std::filesystem::remove_all(dir);
}
