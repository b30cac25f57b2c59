// The command line of the machine side, run as a user runs it (the built `rosmill` binary): `rosmill post`,
// `rosmill plan -o prog.ngc`, and `rosmill send` to a folder (file://) and to the SIMULATED GRBL over TCP
// (test/core/grbl_sim.hpp); bad controller URLs and programs breaking a limit get clear errors, and nothing is sent.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "grbl_sim.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/gcode/rs274_check.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"
#include "test_post_jobs.hpp"

using namespace rosmill::core;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct CliRun {
  int status = -1;
  std::string out, err;
};

// A folder of its own per test, removed afterwards.
class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/rosmill-cli-test-XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // Runs `rosmill ARGS` from the source folder (so config/machine.yaml is found), stdin from /dev/null.
  CliRun rosmill(const std::string& args) const {
    const std::string out = (dir_ / "stdout").string(), err = (dir_ / "stderr").string();
    const std::string cmd = "cd " ROSMILL_SOURCE_DIR " && " ROSMILL_CLI " " + args + " </dev/null >" + out + " 2>" + err;
    const int rc = std::system(cmd.c_str());
    CliRun r;
    r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // A toolpath file of the synthetic raster and cylinder contours.
  std::string toolpath_file() const {
    const std::string p = path("toolpath.json");
    write_toolpath_file(p, Job{test::raster_toolpath(), test::revolution_contours("cylinder", [](double) { return 25.0; }, 6, 3, 360)});
    return p;
  }

  fs::path dir_;
};

}  // namespace

TEST_F(CliTest, PostWritesEachDialectWithArcsWithinTheMachine) {
  const std::string json = toolpath_file();
  CliRun r = rosmill("post " + json + " --dialect grbl --arcs --machine config/machine.yaml -o " + path("prog.nc"));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto grbl = gcode::read_program_lines(path("prog.nc"));
  size_t arcs = 0;
  for (const std::string& l : grbl) {
    EXPECT_LE(l.size(), 80u) << l;
    EXPECT_EQ(l.find("M6"), std::string::npos) << l;
    arcs += l.rfind("G2", 0) == 0 || l.rfind("G3", 0) == 0;
  }
  EXPECT_GT(arcs, 0u);
  EXPECT_NE(r.out.find("\"dialect\":\"grbl\""), std::string::npos) << r.out;

  r = rosmill("post " + json + " --dialect linuxcnc --line-numbers -o " + path("prog.ngc"));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto lcnc = gcode::read_program_lines(path("prog.ngc"));
  EXPECT_EQ(lcnc.front().rfind("N10 ", 0), 0u) << lcnc.front();
  EXPECT_TRUE(gcode::run_rs274(lcnc).ok);

  // A machine whose feed limit the job breaks: refused, naming the line and the limit; no program written.
  std::ofstream(path("slow.yaml")) << "name: slow\nenvelope: {x: [-300, 300], y: [-300, 300], z: [-60, 100]}\n"
                                      "table_z: -55\nmax_feed: 500\nmax_spindle_rpm: 24000\nclearance_over_stock: 2\n";
  r = rosmill("post " + json + " --machine " + path("slow.yaml") + " -o " + path("refused.ngc"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("max feed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("line "), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("refused.ngc")));

  r = rosmill("post " + json + " --dialect fanuc -o " + path("x.ngc"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("unknown dialect 'fanuc'"), std::string::npos) << r.err;
}

TEST_F(CliTest, PlanWritesGcodeWhenTheOutputIsAProgram) {
  ASSERT_EQ(rosmill("primitive cube -o " + path("cube.stl")).status, 0);
  CliRun r = rosmill("plan " + path("cube.stl") + " --strategy contour --tool flat:6@5 --stepdown 20 -o " + path("cube.gcode"));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto lines = gcode::read_program_lines(path("cube.gcode"));
  ASSERT_GT(lines.size(), 10u);
  EXPECT_NE(std::find(lines.begin(), lines.end(), "G17 G21 G40 G49 G54 G80 G90 G94"), lines.end());
  EXPECT_EQ(lines.back(), "M30");
  const gcode::Rs274Result rs = gcode::run_rs274(lines);
  EXPECT_TRUE(rs.ok) << rs.error;
  EXPECT_GT(rs.moves.size(), 8u);
  // The same with the GRBL dialect: a pause instead of M6.
  r = rosmill("plan " + path("cube.stl") + " --strategy contour --tool flat:6@5 --stepdown 20 --dialect grbl -o " +
              path("cube.nc"));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string text = slurp(path("cube.nc"));
  EXPECT_EQ(text.find("M6"), std::string::npos);
  EXPECT_NE(text.find("\nM0\n"), std::string::npos);
}

TEST_F(CliTest, SendToAFolderWritesTheProgramOrItsResumedRest) {
  const std::string json = toolpath_file();
  ASSERT_EQ(rosmill("post " + json + " -o " + path("part.ngc")).status, 0);
  fs::create_directory(path("spool"));
  CliRun r = rosmill("send " + path("part.ngc") + " --controller file://" + path("spool"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(slurp(path("spool/part.ngc")), slurp(path("part.ngc")));
  // Not a terminal: plain progress lines, then the summary.
  EXPECT_NE(r.out.find("progress 100%"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("finished"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << "a progress bar without a terminal";

  // Resumed at line 30: the modal state first, then exactly the lines from 30 on.
  const auto program = gcode::read_program_lines(path("part.ngc"));
  r = rosmill("send " + path("part.ngc") + " --from-line 30 --controller file://" + path("spool"));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto resumed = gcode::read_program_lines(path("spool/part.ngc"));
  ASSERT_GT(resumed.size(), program.size() - 29);
  EXPECT_EQ(resumed.front(), "(rosmill resume at line 30)");
  const size_t rest = program.size() - 30;
  for (size_t i = 0; i < rest; ++i) ASSERT_EQ(resumed[resumed.size() - rest + i], program[30 + i]);
  const gcode::ModalState before = gcode::state_before(program, 29);
  const gcode::ModalState restored = gcode::state_before(resumed, resumed.size() - rest - 1);
  EXPECT_EQ(restored.tool, before.tool);
  EXPECT_EQ(restored.spindle, before.spindle);
  EXPECT_EQ(restored.flood, before.flood);
  EXPECT_LT((restored.position - before.position).norm(), 1e-3);
}

TEST_F(CliTest, SendStreamsToTheSimulatedGrblOverTcp) {
  const std::string json = toolpath_file();
  ASSERT_EQ(rosmill("post " + json + " --dialect grbl --arcs -o " + path("part.nc")).status, 0);
  test::GrblSimulation sim;  // a simulation of GRBL's protocol, not firmware
  const CliRun r = rosmill("send " + path("part.nc") + " --controller grbl+tcp://127.0.0.1:" + std::to_string(sim.port()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("finished"), std::string::npos) << r.out;
  // Every line that carries words reached GRBL once, in order (comments stripped, spaces packed).
  std::vector<std::string> expected;
  for (const std::string& l : gcode::read_program_lines(path("part.nc"))) {
    std::string packed;
    int depth = 0;
    for (char c : l) {
      if (c == '(') ++depth;
      else if (c == ')') --depth;
      else if (depth == 0 && c != ' ') packed.push_back(c);
    }
    if (!packed.empty()) expected.push_back(packed);
  }
  EXPECT_EQ(sim.executed(), expected);
  EXPECT_FALSE(sim.overflowed());
}

TEST_F(CliTest, BadControllersAndViolatingProgramsAreRefusedBeforeSending) {
  const std::string json = toolpath_file();
  ASSERT_EQ(rosmill("post " + json + " -o " + path("part.ngc")).status, 0);
  const std::string prog = path("part.ngc");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"grbl+tcp://localhost", "expected HOST:PORT"},
      {"grbl+tcp://127.0.0.1:99999", "port out of range"},
      {"grbl:///dev/ttyUSB0?speed=9", "unknown option"},
      {"grbl://ttyUSB0", "device path"},
      {"mach3://x:1", "unknown controller kind 'mach3'"},
      {"file://relative/dir", "file:///ABSOLUTE/DIR"},
      {"file:///nonexistent/rosmill/spool", "is not a folder"},
      {"linuxcnc://127.0.0.1", "expected HOST:PORT"},
      {"grbl+tcp://127.0.0.1:1", "cannot connect"},
      {"somewhere", "expected linuxcnc://HOST:PORT"},
  };
  for (const auto& [url, needle] : cases) {
    const CliRun r = rosmill("send " + prog + " --controller '" + url + "'");
    EXPECT_EQ(r.status, 1) << url;
    EXPECT_NE(r.err.find(needle), std::string::npos) << url << ": " << r.err;
  }
  fs::create_directory(path("spool"));
  const std::string spool = " --controller file://" + path("spool");
  EXPECT_NE(rosmill("send " + prog + " --from-line 100000" + spool).err.find("outside the program"), std::string::npos);
  EXPECT_NE(rosmill("send " + path("missing.ngc") + spool).err.find("missing.ngc: no such file"), std::string::npos);

  // A program breaking the envelope: refused with its line and the limit, and nothing reaches the folder.
  auto lines = gcode::read_program_lines(prog);
  const size_t at = lines.size() - 3;
  lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(at), "G0 X400");
  gcode::write_program_lines(path("far.ngc"), lines);
  CliRun r = rosmill("send " + path("far.ngc") + spool);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("line " + std::to_string(at + 1)), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("envelope x max"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(path("spool")));
  // Without a machine file there is no check: refused unless the user says so.
  r = rosmill("send " + prog + spool + " --machine " + path("none.yaml"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--no-limits"), std::string::npos) << r.err;
  EXPECT_EQ(rosmill("send " + prog + spool + " --machine " + path("none.yaml") + " --no-limits").status, 0);

  // --verify: LinuxCNC's interpreter refuses a G1 without feed, and the error names that line.
  gcode::write_program_lines(path("nofeed.ngc"), {"G21 G90 G54", "G0 Z5", "G0 X1 Y1", "G1 X5", "M30"});
  r = rosmill("send " + path("nofeed.ngc") + " --verify --no-limits" + spool);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("nofeed.ngc line 4"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("zero feed rate"), std::string::npos) << r.err;
}
