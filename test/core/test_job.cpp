// Jobs: a job file read with every field checked (errors name the file, line and field); the operations run in
// order on one in-process stock (what the first removed the second does not remove again; the figures add up);
// `rosmill job` writes each operation's program through the checked pipeline and reports it in JSON; LinuxCNC's
// rs274 accepts every program of every example job.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "job_test_options.hpp"
#include "rosmill/testing/sanitized.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/gcode/rs274_check.hpp"
#include "test_stock_programs.hpp"
#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/job/run_job.hpp"

using namespace rosmill::core;
using namespace rosmill::core::job;

namespace {

const std::string kJob = std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/box_cube.yaml";

// The error parse_job gives for `text` (empty when it reads).
std::string error_of(const std::string& text) {
  try {
    parse_job(text, "job.yaml", ROSMILL_SOURCE_DIR);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Job, FieldsAreCheckedWithTheirLine) {
  const std::string ops = "operations:\n  - {strategy: rough, tool: flat:10@1}\n";
  EXPECT_EQ(error_of("part: primitive:cube\n" + ops), "");
  EXPECT_NE(error_of("part: primitive:cube\nresolutoin: 0.5\n" + ops).find("job.yaml:2 resolutoin: unknown field"),
            std::string::npos);
  EXPECT_NE(error_of("part: primitive:cube\nresolution: fine\n" + ops).find("job.yaml:2 resolution: expected a number"),
            std::string::npos);
  EXPECT_NE(error_of("part: primitive:cube\nresolution: 0\n" + ops).find("job.yaml:2 resolution: must lie in"),
            std::string::npos);
  EXPECT_NE(error_of("part: primitive:cube\n").find("operations: missing"), std::string::npos);
  EXPECT_NE(error_of("part: nowhere.stl\n" + ops).find("job.yaml:1 part: no file"), std::string::npos);
  EXPECT_NE(error_of("part: primitive:cube\noperations:\n  - {strategy: rough}\n")
                .find("job.yaml:3 operations[0].tool"),
            std::string::npos);
  EXPECT_NE(error_of("part: primitive:cube\noperations:\n  - {strategy: rough, tool: flat:10@1}\n"
                     "  - {strategy: raster, tool: ball:6@2, stepover: -1}\n")
                .find("job.yaml:4 operations[1].stepover: must lie in"),
            std::string::npos);
  EXPECT_NE(error_of("part: primitive:cube\nstock: {box: {margin: 5}, mesh: a.stl}\n" + ops).find("exactly one of"),
            std::string::npos);
  EXPECT_NE(error_of("part: primitive:cube\noperations:\n  - {strategy: raster, tool: ball:3@3, rest: true}\n")
                .find("job.yaml:3 operations[0].rest: the first operation on a box stock has no earlier one"),
            std::string::npos);
  EXPECT_NE(error_of("part: primitive:cube\noperations: [\n").find("not valid YAML"), std::string::npos);
  // A strategy and a setup the planner does not know: refused when the job runs, naming the operation.
  JobSpec bad = parse_job("part: primitive:cube\n" + ops, "job.yaml", ROSMILL_SOURCE_DIR);
  bad.operations[0].strategy = "sculpt";
  EXPECT_THROW(run_job(bad, {}), Error);
  EXPECT_NE(error_of("part: primitive:cube\noperations:\n  - {strategy: rough, tool: flat:10@1, setup: +W}\n")
                .find("job.yaml:3 operations[0].setup: unknown setup '+W'"),
            std::string::npos);
}

// The package's tool table, which the example jobs name their tools from.
JobOptions with_tools() {
  static const ToolTable tools = read_tool_table(std::string(ROSMILL_SOURCE_DIR) + "/config/tools.yaml");
  JobOptions options;
  options.tools = &tools;
  return options;
}

TEST(Job, OperationsRunOnTheStockTheOnesBeforeLeft) {
  const JobSpec spec = read_job(kJob);
  ASSERT_EQ(spec.operations.size(), 3u);
  const JobReport r = run_job(spec, with_tools());
  ASSERT_EQ(r.operations.size(), 3u);
  // The stock: the cube's bounds grown by 5 mm sideways and up, at 0.5 mm cells that fall on its sides.
  EXPECT_NEAR(r.stock_mm3, 70.0 * 70 * 65, 1e-6);
  EXPECT_NEAR(r.removed_mm3, r.stock_mm3 - r.left_mm3, 1e-6 * r.stock_mm3);
  EXPECT_NEAR(r.removed_mm3, r.operations[0].removed_mm3 + r.operations[1].removed_mm3 + r.operations[2].removed_mm3,
              1e-6 * r.stock_mm3);
  // Every face the job was to finish (the top and the walls; the bottom stands on the table) is within its limit:
  // the top within the ball's scallop, the walls flat.
  EXPECT_EQ(r.surface.asked_faces, 5u);
  EXPECT_EQ(r.surface.unfinished_faces, 0u);
  EXPECT_LE(r.max_left_mm, 0.105);
  // Neither operation cuts into the cube: at least its volume is left.
  EXPECT_GE(r.left_mm3, 60.0 * 60 * 60 - 1e-6);
  // Roughing takes the top down to the allowance over the whole box where it fits: at least the 4.5 mm over the cube.
  EXPECT_GT(r.operations[0].removed_mm3, 60.0 * 60 * 4.5);
  for (const OperationReport& op : r.operations) {
    EXPECT_EQ(op.collision_line, 0u) << op.name;
    EXPECT_GT(op.time_s, 0) << op.name;
    EXPECT_GE(op.air_cut_share, 0) << op.name;
    EXPECT_LT(op.air_cut_share, 1) << op.name;
  }
  // The finish after the roughing removes less than the same finish on the raw box.
  JobSpec finish_only = spec;
  finish_only.operations.erase(finish_only.operations.begin());
  const JobReport alone = run_job(finish_only, with_tools());
  EXPECT_LT(r.operations[1].removed_mm3, alone.operations[0].removed_mm3);
  EXPECT_GT(r.operations[1].air_cut_share, alone.operations[0].air_cut_share);
}

TEST(Job, CommandLineWritesCheckedProgramsAndJson) {
  const std::string dir = ::testing::TempDir() + "rosmill_job_out";
  std::filesystem::remove_all(dir);
  const CliRun run = run_rosmill_in(::testing::TempDir(), "job '" + kJob + "' -o '" + dir + "' --json");
  ASSERT_EQ(run.status, 0) << run.out;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  ASSERT_EQ(j["operations"].size(), 3u);
  for (const auto& op : j["operations"]) {
    EXPECT_TRUE(op.contains("air_cut_share"));
    EXPECT_TRUE(op.contains("removed_mm3"));
    EXPECT_TRUE(op.contains("time_s"));
    EXPECT_TRUE(std::filesystem::exists(op["program"].get<std::string>())) << op.dump();
  }
  EXPECT_TRUE(j.contains("air_cut_share") && j.contains("removed_mm3") && j.contains("time_s"));
  // Every operation is in the +Z setup: one program, with a tool change before each operation's tool.
  const std::string program = j["operations"][0]["program"];
  EXPECT_EQ(j["operations"][1]["program"], program);
  EXPECT_EQ(j["operations"][2]["program"], program);
  size_t changes = 0;
  for (const std::string& line : gcode::read_program_lines(program)) changes += line.find("M6") != std::string::npos;
  EXPECT_EQ(changes, 3u) << program;
  EXPECT_FALSE(j["unfinished"].get<bool>());
  // On request, one program per operation.
  const CliRun apart = run_rosmill_in(::testing::TempDir(), "job '" + kJob + "' -o '" + dir + "' --per-operation --json");
  ASSERT_EQ(apart.status, 0) << apart.out;
  const nlohmann::json k = nlohmann::json::parse(apart.out);
  EXPECT_NE(k["operations"][0]["program"], k["operations"][1]["program"]);
  const CliRun text = run_rosmill_in(::testing::TempDir(), "job '" + kJob + "'");
  EXPECT_EQ(text.status, 0);
  EXPECT_NE(text.out.find("rough"), std::string::npos);
  const CliRun missing = run_rosmill_shell("job /nonexistent/job.yaml 2>&1");
  EXPECT_NE(missing.status, 0);
  EXPECT_NE(missing.out.find("/nonexistent/job.yaml: no such file"), std::string::npos) << missing.out;
  std::filesystem::remove_all(dir);
}

TEST(Job, CastStockFromAMesh) {
  // A casting 2 mm larger than the cube all round, 4 mm on top, written as STL next to the job.
  const std::string dir = ::testing::TempDir() + "rosmill_job_cast";
  std::filesystem::create_directories(dir);
  write_stl(dir + "/cast.stl", build_mesh(stock_test::box_corners(Vec3(-2, -2, 0), Vec3(62, 62, 64))));
  const JobSpec spec = parse_job("part: primitive:cube\nresolution: 0.5\nstock: {mesh: cast.stl}\noperations:\n"
                                 "  - {strategy: rough, tool: flat:10@1, stepover: 4, stepdown: 2, allowance: 0.5}\n",
                                 "job.yaml", dir);
  const JobReport r = run_job(spec, {});
  EXPECT_NEAR(r.stock_mm3, 64.0 * 64 * 64, 1e-6);
  EXPECT_GE(r.left_mm3, 60.0 * 60 * 60 - 1e-6);
  // Levels 2 mm apart from the casting's top: the first, at 62, clears the whole top (the next over the cube would
  // leave less than the allowance, so the roughing goes down beside it only where the cutter fits).
  EXPECT_GE(r.removed_mm3, 64.0 * 64 * 2 - 1e-6);
  EXPECT_EQ(r.operations[0].collision_line, 0u);
  // The same job from the box around the cube cuts more air.
  JobSpec box = spec;
  box.stock = StockSpec{};
  EXPECT_GT(run_job(box, {}).operations[0].air_cut_share, r.operations[0].air_cut_share);
  std::filesystem::remove_all(dir);
}

// The example jobs run as they are, from any folder. A casting holds less material than the box around the part
// (the scanned block as much), and roughing that plans on the stock cuts clearly less air from it than roughing
// planned without it; the roughing's air-cutting share from each is printed.
TEST(Job, ExampleJobsRunFromAnyFolder) {
  const std::string dir = ::testing::TempDir() + "rosmill_job_examples";
  for (const char* name : {"box_cube", "cast_cone", "scanned_dome", "rest_pocket"}) {
    const std::string file = std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/" + name + ".yaml";
    std::filesystem::remove_all(dir);
    const CliRun run = run_rosmill_in(::testing::TempDir(), "job '" + file + "' -o '" + dir + "' --json");
    ASSERT_EQ(run.status, 0) << name << ": " << run.out;
    const nlohmann::json j = nlohmann::json::parse(run.out);
    EXPECT_GT(j["removed_mm3"].get<double>(), 0.0) << name;
    // No operation cuts below the design by more than 0.001 mm (the stock model's view of the part).
    EXPECT_GE(j["min_left_mm"].get<double>(), -0.001) << name;
    EXPECT_GE(j["max_left_mm"].get<double>(), j["min_left_mm"].get<double>()) << name;
    // The verifier, simulating each program on its own grid, finds no gouge either: the two models agree.
    EXPECT_EQ(j["gouge_mm"].get<double>(), 0.0) << name;
    std::set<std::string> programs;
    for (const auto& op : j["operations"]) {
      EXPECT_TRUE(std::filesystem::exists(op["program"].get<std::string>())) << name << ": " << op.dump();
      programs.insert(op["program"].get<std::string>());
      EXPECT_EQ(op["gouge_mm"].get<double>() > 0, op["min_left_mm"].get<double>() < -0.01) << name << ": " << op.dump();
    }
    // Every program the job wrote is accepted by LinuxCNC's own interpreter.
    for (const std::string& path : programs) {
      std::ifstream in(path);
      std::vector<std::string> lines;
      for (std::string line; std::getline(in, line);) lines.push_back(line);
      const gcode::Rs274Result r = gcode::run_rs274(lines);
      EXPECT_TRUE(r.ok) << name << ": " << path << " line " << r.error_line << ": " << r.error;
      EXPECT_GT(r.moves.size(), 10u) << name << ": " << path;
    }
    // Under the sanitizers the roughing's air is compared on one job: three more runs of each take minutes there.
    if (std::string(name) == "box_cube" || (rosmill::testing::kSanitized && std::string(name) != "cast_cone")) continue;
    const JobOptions options = with_tools();
    JobSpec spec = read_job(file);
    spec.operations.resize(1);  // the roughing
    const JobReport real = run_job(spec, options);
    JobOptions blind = options;  // planned as before jobs knew the stock: on the box or the stock mesh alone
    blind.plan_on_stock = false;
    const JobReport before = run_job(spec, blind);
    spec.stock = StockSpec{};  // the box around the part, 5 mm larger
    const JobReport box = run_job(spec, options);
    std::printf("%s: roughing air-cutting share %.3f planned on its own stock (%.3f planned without it), %.3f from "
                "the box\n", name, real.operations[0].air_cut_share, before.operations[0].air_cut_share,
                box.operations[0].air_cut_share);
    if (std::string(name) == "scanned_dome") {
      // The scanned block is as large as the box: its top, 55 + 2 sin(x / 15) cos(y / 20) mm over 110 x 110 mm
      // (config/jobs/data/README.md), averages 55 mm (the wave's integral over the square is 0): 665,500 mm3.
      EXPECT_NEAR(real.stock_mm3, 110.0 * 110.0 * 55.0, 0.005 * 110.0 * 110.0 * 55.0);
    } else {
      EXPECT_LT(real.stock_mm3, box.stock_mm3) << name;
    }
    // Half the air or less where the stock is far from the part (a cone from a cylinder, a scanned block); the
    // pocket's casting is near-net (2 mm all round), so there is less air to save: still less than before.
    const double bound = std::string(name) == "rest_pocket" ? 1.0 : 0.5;
    EXPECT_LT(real.operations[0].air_cut_share, bound * before.operations[0].air_cut_share) << name;
    EXPECT_GT(real.operations[0].removed_mm3, 0.0) << name;
  }
  std::filesystem::remove_all(dir);
}

// The progress hook of a long job (the PlanJob action's feedback and cancel): called per operation with a
// fraction that rises from 0 to 1; answering false stops the job and keeps the operations already finished.
TEST(Job, ProgressReportsEachOperationAndCancelKeepsTheFinishedOnes) {
  const JobSpec spec = read_job(kJob);
  JobOptions options = with_tools();
  std::vector<std::pair<size_t, double>> calls;
  options.progress = [&](size_t op, double f) {
    calls.emplace_back(op, f);
    return true;
  };
  const JobReport full = run_job(spec, options);
  EXPECT_FALSE(full.cancelled);
  ASSERT_EQ(full.operations.size(), 3u);
  ASSERT_GE(calls.size(), 4u);
  for (size_t i = 1; i < calls.size(); ++i) {
    // Never backwards: the operation index grows, and within one operation the fraction does too.
    ASSERT_GE(calls[i].first, calls[i - 1].first);
    if (calls[i].first == calls[i - 1].first) {
      EXPECT_GE(calls[i].second, calls[i - 1].second);
    }
  }
  EXPECT_EQ(calls.front(), std::make_pair(size_t(0), 0.0));
  EXPECT_EQ(calls.back(), std::make_pair(size_t(2), 1.0));
  EXPECT_GT(calls.size(), 6u) << "progress is reported while an operation is planned, not only between them";

  // Cancelled while the second operation is planned: the first is kept with its figures, the second is not run.
  options.progress = [](size_t op, double f) { return op == 0 || f < 0.3; };
  const JobReport stopped = run_job(spec, options);
  EXPECT_TRUE(stopped.cancelled);
  ASSERT_EQ(stopped.operations.size(), 1u);
  EXPECT_NEAR(stopped.operations[0].removed_mm3, full.operations[0].removed_mm3, 1e-6);
  EXPECT_NEAR(stopped.left_mm3, stopped.stock_mm3 - full.operations[0].removed_mm3, 1e-6 * stopped.stock_mm3);
  // Cancelled before anything: nothing removed.
  options.progress = [](size_t, double) { return false; };
  const JobReport none = run_job(spec, options);
  EXPECT_TRUE(none.cancelled);
  EXPECT_TRUE(none.operations.empty());
  EXPECT_NEAR(none.left_mm3, none.stock_mm3, 1e-9);
}

// Every tool of a job is loaded by its number: an inline tool without one is refused with its line before anything
// is planned; `flat:4@6` and {number: 6, type: flat, diameter: 4} name the same tool; two cutters under one number
// are refused.
TEST(Job, InlineToolsNeedTheirNumber) {
  const std::string head = "part: primitive:cube\noperations:\n  - {strategy: rough, tool: 1}\n";
  const std::string unnumbered = error_of(head + "  - {strategy: waterline, tool: flat:4}\n");
  EXPECT_NE(unnumbered.find("job.yaml:4 operations[1].tool: 'flat:4' has no number in the controller's tool table: "
                            "write flat:4@N"),
            std::string::npos)
      << unnumbered;
  EXPECT_EQ(error_of(head + "  - {strategy: waterline, tool: flat:4@6}\n"), "");
  const JobSpec mapped =
      parse_job(head + "  - {strategy: waterline, tool: {number: 6, type: flat, diameter: 4}}\n", "job.yaml", ".");
  EXPECT_EQ(mapped.operations[1].tool, "flat:4@6");
  EXPECT_NE(error_of(head + "  - {strategy: waterline, tool: {type: flat, diameter: 4}}\n").find("number: missing"),
            std::string::npos);
  EXPECT_NE(error_of(head + "  - {strategy: waterline, tool: {number: 6, type: drill, diameter: 4}}\n")
                .find("must be flat, ball or bull, got 'drill'"),
            std::string::npos);
  EXPECT_NE(error_of(head + "  - {strategy: waterline, tool: {number: 6, type: flat, diameter: 4, corner_radius: 1}}\n")
                .find("only a bull nose"),
            std::string::npos);
  // T1 of the table is the 10 mm end mill: a 4 mm cutter under its number is another tool.
  const std::string dir = ::testing::TempDir();
  std::string clash;
  try {
    run_job(parse_job(head + "  - {strategy: waterline, tool: flat:4@1}\n", "job.yaml", dir), job_test::options());
  } catch (const Error& e) {
    clash = e.what();
  }
  EXPECT_NE(clash.find("operations[1].tool: tool T1 is another cutter in operations[0] (1): one number, one tool"),
            std::string::npos)
      << clash;
}
