// What the fuzz targets (test/fuzz) and reading the readers beside them found, each with its input: every one is
// now read or refused with rosmill's Error naming the place, where it escaped as another exception, read past its
// data, or was accepted with a value that is not a number.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>

#include "../fuzz/fuzz_transport.hpp"
#include "error_of.hpp"
#include "rosmill/control/grbl.hpp"
#include "rosmill/control/linuxcnc.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/job/job_spec.hpp"
#include "rosmill/planner/presets.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"

namespace {

using namespace rosmill::core;

std::string temp_file(const std::string& name, const std::string& bytes) {
  const std::string path = ::testing::TempDir() + "/" + std::to_string(::getpid()) + "_" + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// fuzz_tables: a tool entry whose field name is a sequence escaped as yaml-cpp's bad conversion.
TEST(FuzzFindings, ToolFieldNameThatIsNotTextIsRefused) {
  const std::string input = "\ntools:\n- {[]}";
  EXPECT_NE(error_of([&] { parse_presets(input, "presets.yaml"); }).find("a field's name must be a text"),
            std::string::npos);
  EXPECT_NE(error_of([&] { parse_tool_table(input, "tools.yaml"); }).find("tools.yaml:3 tools[0]"), std::string::npos);
}

// fuzz_tables: a template's weight that is not a number escaped as yaml-cpp's bad conversion (the fuzzer's input
// was the whole presets file with one weight garbled; this is that weight alone). A negative share is refused too.
TEST(FuzzFindings, TemplateWeightThatIsNotANumberIsRefused) {
  const std::string table =
      "tools: [{id: 1, type: flat, diameter: 10, flute_length: 20, shank_diameter: 6, spindle_rpm: 8000,\n"
      "         feed: 1200, plunge_feed: 300, stepover: 5, stepdown: 2}]\n"
      "presets: [{name: a, strategy: raster, tool: 1}, {name: b, strategy: raster, tool: 1}]\n";
  for (const std::string weights : {"[0.5, x]", "[1.5, -0.5]", "{a: 1}"}) {
    const std::string text = table + "templates: [{name: t, stages: [a, b], weights: " + weights + "}]\n";
    const std::string message = error_of([&] { parse_presets(text, "presets.yaml"); });
    EXPECT_NE(message.find("presets.yaml"), std::string::npos) << weights;
  }
  const PresetTable good = parse_presets(table + "templates: [{name: t, stages: [a, b], weights: [0.25, 0.75]}]\n",
                                         "presets.yaml");
  ASSERT_EQ(good.templates.size(), 1u);
  EXPECT_DOUBLE_EQ(good.templates[0].weights[1], 0.75);
}

// fuzz_tables: a machine name that is a sequence ("name: []", after the selector byte 2) escaped as yaml-cpp's bad
// conversion.
TEST(FuzzFindings, MachineNameThatIsNotTextIsRefused) {
  EXPECT_NE(error_of([] {
              gcode::parse_machine_limits("name: []", "machine.yaml");
            }).find("machine.yaml:1 name: expected a text"),
            std::string::npos);
}

// fuzz_job_yaml: a part name longer than a file name may be made std::filesystem::exists() throw its own error.
TEST(FuzzFindings, JobPartNameTheSystemCannotLookUpIsRefused) {
  const char input[] =
      "{part: 'xrimvestrategy:O-\xbd"
      "9Lo\xb4\xec\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3"
      "\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3"
      "\xc3\xc3\xc3\xc3\xc3\xc3# A con machml -o out\n"
      "part: primiion: 0.5\n"
      "rapid_feed: 5000\n"
      "stock: mesh: primitie:cylinder\n"
      "operation\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3   \xc3\xc3"
      "\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3"
      "esh:presttool}, p   \xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3\xc3"
      "esh:prtivtool'},";
  const std::string message = error_of([&] { job::parse_job(input, "job.yaml", ROSMILL_SOURCE_DIR "/config/jobs"); });
  EXPECT_NE(message.find("job.yaml:1 part: cannot look up"), std::string::npos) << message;
  EXPECT_NE(message.find("too long"), std::string::npos) << message;
}

// fuzz_cloud: a coordinate finite in metres (the PCD's doubles) but beyond the largest double once in millimetres
// came back as infinity; such a point is dropped, like a NaN.
TEST(FuzzFindings, CloudPointInfiniteInMillimetresIsDropped) {
  const char input[] =
      "FIELDS x y z\n"
      "SIZE 8 8 8\n"
      "TYPE F F F\n"
      "WIDTH 2\n"
      "HEIGHT 2\n"
      "POINTS 4\n"
      "DATA binary\n"
      "# .\n"
      "VNRSIOE 0.\xfa\n"
      "F5\x00\x00\x00\xf8\n"
      "TYPS 4\n"
      "DATA binary\n"
      "\x00\x00\x00\x00\xc0\x7f\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00"
      "\x00\x00\x00\x00\x00\x00\x00\x00TYP{\x14\xaeG\xe1z\x84\x00\x00\x00\x00\x00\x00z\x84\x00"
      "\x00\x00\x00\x00\x00";
  const std::string path = temp_file("huge.pcd", std::string(input, sizeof input - 1));
  CloudInfo info;
  const PointCloud cloud = read_cloud(path, {}, &info);
  EXPECT_EQ(info.points_in_file, 4u);
  EXPECT_EQ(cloud.points.size() + info.dropped_nonfinite, 4u);
  EXPECT_GE(info.dropped_nonfinite, 1u);
  for (const Vec3& p : cloud.points) EXPECT_TRUE(p.allFinite()) << p.transpose();
  ::unlink(path.c_str());
}

// fuzz_cloud: PCL's PCD reader goes on reading header lines after DATA; a COUNT there with a word that is not a
// number left a field's count uninitialised, and PCL allocated a point step of that garbage (ASan: an allocation of
// 100 TB). Such lines are refused, as are the other ways the header could be read differently by PCL and the check.
TEST(FuzzFindings, PcdHeaderThatPclReadsDifferentlyIsRefused) {
  const std::string head = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\n";
  const std::pair<std::string, std::string> cases[] = {
      {head + "DATA ascii\nCOUNT 1 x 1\n1 2 3\n", "a 'COUNT' header line after DATA"},
      {head + "DATA ascii\n# a comment\n  SIZE 8 8 8\n1 2 3\n", "a 'SIZE' header line after DATA"},
      {"FIELDS x\vy z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2 3\n", "control character"},
      {head + "SIZE 8 8 8\nDATA ascii\n1 2 3\n", "a second 'SIZE' line"},
      {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2000000000\nPOINTS 2000000000\nDATA ascii\n1 2 3\n",
       "truncated PCD"},
      {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 4294967296\nDATA binary\n", "exceeds"},
      {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 99999999\nWIDTH 1\nDATA binary\n", "exceeds"},
  };
  for (const auto& [input, expected] : cases) {
    const std::string path = temp_file("header.pcd", input);
    const std::string message = error_of([&] { read_cloud(path); });
    EXPECT_NE(message.find(expected), std::string::npos) << "input:\n" << input << "\nmessage: " << message;
    ::unlink(path.c_str());
  }
  // The same header with its points and nothing after DATA is read.
  const std::string path = temp_file("good.pcd", head + "DATA ascii\n1 2 3\n");
  EXPECT_EQ(read_cloud(path).points.size(), 1u);
  ::unlink(path.c_str());
}

// fuzz_cloud: a list property in the PLY vertex element (here a face's vertex_indices after an element line the
// fuzzer turned into a comment) made PCL's reader assert and abort the process. It is refused before PCL reads it.
TEST(FuzzFindings, PlyVertexListPropertyIsRefused) {
  const std::string input =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0 1 5\n1 1 1 3 1 2 3\n";
  const std::string path = temp_file("list.ply", input);
  const std::string message = error_of([&] { read_cloud(path); });
  EXPECT_NE(message.find("PLY vertex property 'vertex_indices' is a list"), std::string::npos) << message;
  ::unlink(path.c_str());
}

// Toolpath files: a field of the wrong JSON type escaped as nlohmann's type_error (found reading the reader, then
// run through fuzz_toolpath_json); an id beyond int was converted with undefined behaviour; a move type of 2^32 + 1
// was read as 1.
TEST(FuzzFindings, ToolpathFieldsOfTheWrongTypeAreRefused) {
  const std::string tool = R"("tool":{"id":2,"name":"b","type":"ball","diameter":6,"corner_radius":3,)"
                           R"("flute_length":20,"shank_diameter":6,"spindle_rpm":1,"feed":1,"plunge_feed":1,)"
                           R"("stepover":1,"stepdown":1})";
  const auto file = [&](const std::string& toolpath) {
    return R"({"format":"rosmill-toolpath","units":"mm","toolpaths":[{"safe_z":5,"clearance_z":2,"start":[0,0,5],)" +
           toolpath + "}]}";
  };
  const std::pair<std::string, std::string> cases[] = {
      {R"({"format":1})", "field 'format' is not a text"},
      {R"({"format":"rosmill-toolpath","units":["mm"],"toolpaths":[]})", "field 'units' is not a text"},
      {file(tool + R"(,"strategy":5,"passes":[])"), "field 'strategy' is not a text"},
      {file(tool + R"(,"passes":[[1]])"), "pass 0: pass is not an object"},
      {file(tool + R"(,"passes":[{"name":{},"moves":[]}])"), "field 'name' is not a text"},
      {file(tool + R"(,"passes":[{"moves":[[0,0,0,4294967297,1]]}])"), "move type must be 0"},
      {file(R"("tool":{"id":1e300,"type":"flat","diameter":6})" R"(,"passes":[])"), "field 'id' must lie in"},
  };
  for (const auto& c : cases)
    EXPECT_NE(error_of([&] { parse_toolpath_text(c.first, "tp.json"); }).find(c.second), std::string::npos) << c.first;
  const std::vector<Toolpath> job = parse_toolpath_text(file(tool + R"(,"passes":[{"moves":[[1,2,3,1,100]]}])"), "t");
  ASSERT_EQ(job.size(), 1u);
  EXPECT_EQ(job[0].passes[0].moves[0].type, MoveType::Feed);
}

// GRBL: a status report whose position is cut short ("MPos:1") was read on past the end of the reply (strtod from
// one byte beyond it) and taken as a position.
TEST(FuzzFindings, GrblStatusCutShortLeavesThePositionUnknown) {
  const auto status_after = [](const std::string& replies) {
    control::ControllerOptions options;
    options.status_interval_s = 0;
    control::GrblController grbl([&] { return std::make_unique<rosmill::fuzz::ScriptedPeer>(replies); }, "grbl",
                                 options, 0.0);
    grbl.connect();
    grbl.start({"G0 X1", "M2"}, {});
    return grbl.poll(0.05);
  };
  const std::string long_state = "<Idle|AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA|";
  EXPECT_FALSE(status_after(long_state + "MPos:1\n").position_known);
  EXPECT_FALSE(status_after(long_state + "MPos:1,2\n").position_known);
  EXPECT_FALSE(status_after("<Idle|MPos:1,,3>\n").position_known);
  const control::ControllerStatus full = status_after("<Idle|MPos:1.5,-2,3.25,7|FS:0,0>\n");
  ASSERT_TRUE(full.position_known);
  EXPECT_EQ(full.position, Vec3(1.5, -2, 3.25));
}

// fuzz_linuxcnc: a PROGRAM_LINE beyond the program (7 of a 6-line program) was taken as the current line and
// moved the acknowledged line past the program's end.
TEST(FuzzFindings, LinuxcncLineBeyondTheProgramIsNotTaken) {
  const std::string replies =
      "HELLO ACK EMCNETSVR 1.1\r\nSET VERBOSE ACK\r\nSET ENABLE ACK\r\nSET SET_WAIT ACK\r\nSET TIMEOUT ACK\r\n"
      "SET ESTOP ACK\r\nSET WAIT ACK\r\nSET MACHINE ACK\r\nSET WAIT ACK\r\n"
      "ERROR OK\r\nSET MODE ACK\r\nSET WAIT ACK\r\nSET OPEN ACK\r\nSET WAIT ACK\r\nERROR OK\r\nSET RUN ACK\r\n"
      "PROGRAM_STATUS RUNNING\r\nPROGRAM_LINE 2\r\nABS_ACT_POS 1.0 2.0 3.0 0 0 0\r\nERROR OK\r\n"
      "PROGRAM_STATUS RUNNING\r\nPROGRAM_LINE 7\r\nABS_ACT_POS 1.0 2.0 3.0 0 0 0\r\nERROR OK\r\n";
  control::ControllerOptions options;
  options.program_dir = ::testing::TempDir();
  options.program_name = "fuzz_finding_" + std::to_string(::getpid()) + ".ngc";
  options.home_if_needed = false;
  control::LinuxcncController cnc("test", 5007, options,
                                  [&] { return std::make_unique<rosmill::fuzz::ScriptedPeer>(replies); });
  cnc.connect();
  cnc.start({"G21 G90", "G0 Z5", "G1 Z-1 F300", "X10", "G0 Z5", "M2"}, {});
  const control::ControllerStatus first = cnc.poll(0.0);
  EXPECT_EQ(first.current_line, 2u);
  const control::ControllerStatus second = cnc.poll(0.0);
  EXPECT_EQ(second.current_line, 2u);
  EXPECT_EQ(second.acknowledged_line, 1u);
  EXPECT_LE(second.acknowledged_line, second.total_lines);
  const std::string pid = std::to_string(::getpid());
  ::unlink((options.program_dir + "/fuzz_finding_" + pid + "-" + pid + "-1.ngc").c_str());
}

}  // namespace
