// The verifier's RS274 reader: what each word means for the motion, the tools, and errors that name the line.
#include <gtest/gtest.h>

#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/toolpath/canon_arc.hpp"
#include "rosmill/verify/gcode_reader.hpp"

using namespace rosmill::core;
using namespace rosmill::core::verify;
using namespace rosmill::core::stock;

namespace {

// T1 a 6 mm ball (in the spindle at the start), T2 a 10 mm flat end.
MachineProgram parse(const std::string& text) {
  return parse_gcode(text, "p.ngc", tool_setup({"1=ball:6", "2=flat:10", "1"}));
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(VerifyGcode, LinesUnitsAndDistanceModes) {
  const MachineProgram p = parse(
      "%\n(header) N10 G21 G90 G17\nG0 X1 Y2 Z3 ; go\nG1X4Y5F100\nG91 G1 X1 Z-1\nG20 G1 X1\nG90 G21 G0 Z10\n%\n");
  ASSERT_EQ(p.moves.size(), 5u);
  EXPECT_TRUE(p.from_gcode);
  EXPECT_EQ(p.moves[0].source, 3u);
  EXPECT_TRUE(p.moves[0].rapid);
  EXPECT_EQ(p.moves[0].from, Vec3(1, 2, 3));  // the first move starts at its own target
  EXPECT_EQ(p.moves[1].to, Vec3(4, 5, 3));
  EXPECT_FALSE(p.moves[1].rapid);
  EXPECT_EQ(p.moves[2].to, Vec3(5, 5, 2));    // incremental
  EXPECT_NEAR(p.moves[3].to.x(), 5 + 25.4, 1e-12);  // one inch more, still incremental
  EXPECT_EQ(p.moves[4].to, Vec3(30.4, 5, 10));
  EXPECT_EQ(p.moves[4].source, 7u);
}

TEST(VerifyGcode, InchProgramsAreReadInMillimetres) {
  const MachineProgram p = parse("G20 G90 G17\nG0 X0 Y0 Z0.5\nG1 Z-0.1 F10\nG2 X1 Y0 I0.5 J0\nG3 X0 Y0 R0.5\n");
  ASSERT_EQ(p.moves.size(), 4u);
  EXPECT_NEAR(p.moves[1].to.z(), -2.54, 1e-12);
  EXPECT_NEAR(p.moves[2].to.x(), 25.4, 1e-12);
  EXPECT_NEAR((p.moves[2].centre - Vec2(12.7, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR(arc_sweep(p.moves[2]), -M_PI, 1e-12);
  EXPECT_NEAR((p.moves[3].centre - Vec2(12.7, 0)).norm(), 0, 1e-9);  // R in inches too
}

TEST(VerifyGcode, PositionsAreUnknownUntilEveryAxisIsGiven) {
  // The controller's position before the program is unknown: "G0 Z5" alone moves from somewhere, so nothing is
  // swept until X, Y and Z are all known; the first swept move starts at its own target.
  const MachineProgram p = parse("G0 Z5\nG91 G0 X3\nG90 G0 X1 Y2\nG1 Z0\n");
  ASSERT_EQ(p.moves.size(), 2u);
  EXPECT_EQ(p.moves[0].source, 3u);
  EXPECT_EQ(p.moves[0].from, Vec3(1, 2, 5));
  EXPECT_EQ(p.moves[0].to, Vec3(1, 2, 5));
  EXPECT_EQ(p.moves[1].to, Vec3(1, 2, 0));
  EXPECT_NE(error_of("G0 Z5\nG2 X1 Y0 I1\n").find("first move"), std::string::npos);
}

TEST(VerifyGcode, ProgramEndsAtM2M30OrTheClosingPercent) {
  EXPECT_EQ(parse("G0 X0 Y0 Z5\nG1 X1\nM30\nG1 X2\n").moves.size(), 2u);
  EXPECT_EQ(parse("G0 X0 Y0 Z5\nG1 X1 M2\nG1 X2\n").moves.size(), 2u);  // the move of the M2 line still runs
  EXPECT_EQ(parse("%\nG0 X0 Y0 Z5\nG1 X1\n%\nG1 X2\n").moves.size(), 2u);
  EXPECT_EQ(error_of("G0 X0 Y0 Z5\nM30\nG5 X1\n"), "");  // nothing after the end is read
}

TEST(VerifyGcode, ArcsByCentreAndRadius) {
  const MachineProgram p = parse("G0 X10 Y0 Z0\nG3 X0 Y10 I-10 J0\nG2 X10 Y0 R10\nG3 X-10 Y0 I-10 Z-2\nG3 X-10 Y0 I10\n");
  ASSERT_EQ(p.moves.size(), 5u);
  EXPECT_EQ(p.moves[1].shape, MoveShape::ArcCCW);
  EXPECT_NEAR((p.moves[1].centre - Vec2(0, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR(arc_sweep(p.moves[1]), M_PI / 2, 1e-12);
  // G2 from (0,10) to (10,0) with R10: the short way round, centre (0,0).
  EXPECT_NEAR((p.moves[2].centre - Vec2(0, 0)).norm(), 0, 1e-9);
  EXPECT_NEAR(arc_sweep(p.moves[2]), -M_PI / 2, 1e-9);
  // A helical half turn, then a full circle by I (end = start).
  EXPECT_NEAR(arc_sweep(p.moves[3]), M_PI, 1e-12);
  EXPECT_EQ(p.moves[3].to.z(), -2.0);
  EXPECT_NEAR(move_point(p.moves[3], 0.5).y(), 10, 1e-12);
  EXPECT_NEAR(arc_sweep(p.moves[4]), 2 * M_PI, 1e-12);
  EXPECT_THROW(parse("G0 X1 Y0 Z0\nG2 X1 Y0 R2\n"), Error);
}

TEST(VerifyGcode, LongArcByNegativeRadius) {
  const MachineProgram p = parse("G0 X0 Y10 Z0\nG2 X10 Y0 R-10\n");
  EXPECT_NEAR((p.moves[1].centre - Vec2(10, 10)).norm(), 0, 1e-9);
  EXPECT_NEAR(arc_sweep(p.moves[1]), -1.5 * M_PI, 1e-9);
}

TEST(VerifyGcode, ToolChanges) {
  const MachineProgram p = parse("G0 X0 Y0 Z5\nT2 M6\nG1 X1\nT1\nG1 X2\nM6\nG1 X3\n");
  ASSERT_EQ(p.moves.size(), 4u);
  EXPECT_EQ(p.tools[p.moves[0].tool].cutter.type, CutterType::BallEnd);  // the one loaded at the start
  EXPECT_EQ(p.tools[p.moves[1].tool].cutter.type, CutterType::FlatEnd);
  EXPECT_EQ(p.tools[p.moves[2].tool].cutter.type, CutterType::FlatEnd);  // T1 only selects
  EXPECT_EQ(p.tools[p.moves[3].tool].cutter.type, CutterType::BallEnd);
  // Two tools and none loaded: a move before the first M6 has no tool.
  const ToolSetup two = tool_setup({"1=ball:6", "2=flat:10"});
  EXPECT_THROW(parse_gcode("G0 X0 Y0 Z5\n", "p.ngc", two), Error);
  EXPECT_EQ(parse_gcode("T2 M6\nG0 X0 Y0 Z5\n", "p.ngc", two).tools[0].cutter.type, CutterType::FlatEnd);
}

TEST(VerifyGcode, ToolSetupFromTheTableAndSpecs) {
  const ToolTable table = read_tool_table(ROSMILL_SOURCE_DIR "/config/tools.yaml");
  const ToolSetup s = tool_setup({"T3=bull:8:1", "7=flat:2", "2"}, &table);
  EXPECT_EQ(s.tools.at(1).cutter.type, CutterType::FlatEnd);  // the table's T1
  EXPECT_EQ(s.tools.at(3).cutter.type, CutterType::BullNose);  // replaced by the spec
  EXPECT_EQ(s.tools.at(7).cutter.diameter, 2.0);
  ASSERT_TRUE(s.loaded);
  EXPECT_EQ(s.loaded->cutter.type, CutterType::BallEnd);       // the table's T2, 6 mm ball
  EXPECT_EQ(s.loaded->cutter.diameter, 6.0);
  EXPECT_EQ(tool_setup({"ball:4"}).loaded->cutter.diameter, 4.0);
  EXPECT_THROW(tool_setup({"ball:4", "flat:2"}), Error);       // two tools loaded at the start
  EXPECT_THROW(tool_setup({"T1=flat:2", "1=ball:3"}), Error);  // T1 twice
  EXPECT_THROW(tool_setup({"ball"}), Error);
  EXPECT_THROW(tool_setup({"x=ball:3"}), Error);
  EXPECT_THROW(tool_setup({"9"}, &table), Error);              // not in the table
}

TEST(VerifyGcode, UnsupportedMotionNamesTheLine) {
  EXPECT_NE(error_of("G0 X0 Y0 Z0\nG18\n").find("p.ngc:2"), std::string::npos);
  EXPECT_NE(error_of("G0 X0\n\nG41 D1\n").find("p.ngc:3"), std::string::npos);
  EXPECT_NE(error_of("G81 X0 Y0 Z-1 R1\n").find("p.ngc:1: G81"), std::string::npos);
  EXPECT_NE(error_of("G28\n").find("G28"), std::string::npos);
  EXPECT_NE(error_of("G59.1\n").find("G59.1"), std::string::npos);
  EXPECT_NE(error_of("G10 L2 P7 X0 Y0 Z0\n").find("G10 other than L2 P1..P6"), std::string::npos);
  // A setup's own system: the program's coordinates are the part's, whichever system holds them.
  EXPECT_EQ(error_of("G10 L2 P2 X5 Y6 Z-40\nG17 G21 G90 G55\nG0 X0 Y0 Z0\n"), "");
  EXPECT_NE(error_of("G0 X#1\n").find("p.ngc:1"), std::string::npos);
  EXPECT_NE(error_of("G0 X0 Y0 Z0\nG2 X10 Y0 I3\n").find("p.ngc:2: radius"), std::string::npos);
  EXPECT_NE(error_of("X1\n").find("motion mode"), std::string::npos);
  EXPECT_NE(error_of("G0 X1 X2\n").find("twice"), std::string::npos);
  EXPECT_NE(error_of("G0 G1 X1\n").find("in one line"), std::string::npos);
  EXPECT_NE(error_of("G1 X1 (open\n").find("comment"), std::string::npos);
  EXPECT_NE(error_of("O100 sub\n").find("O-words"), std::string::npos);
  EXPECT_NE(error_of("G0 X0 Y0 Z0\nG2 X0 Y0 I5 P2\n").find("turns"), std::string::npos);
  EXPECT_EQ(error_of("G54 G40 G49 G64 P0.01 G94 M3 S1000 M8\nG4 P1\nG43 H1\nM5 M9 M30\n"), "");
}

TEST(VerifyGcode, UnknownWordsAndToolsNameTheLine) {
  EXPECT_NE(error_of("G0 X0 Y0 Z0\nG1 X1 A10\n").find("p.ngc:2: axis A"), std::string::npos);
  EXPECT_NE(error_of("G1 X1 Q2\n").find("word Q"), std::string::npos);
  EXPECT_NE(error_of("G1 X1 E2\n").find("word E"), std::string::npos);
  EXPECT_NE(error_of("M72\n").find("M72"), std::string::npos);
  EXPECT_NE(error_of("M42\n").find("M42 is not known"), std::string::npos);
  EXPECT_NE(error_of("G0 X0 Y0 Z5\nT9\n").find("p.ngc:2: tool T9 is not in the tool table"), std::string::npos);
  EXPECT_NE(error_of("T9 M6\n").find("T9"), std::string::npos);
  EXPECT_NE(error_of("M6\n").find("without a T"), std::string::npos);
}
