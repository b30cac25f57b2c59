// The one G-code reader: the lexer (comments, block delete, line numbers, '%' lines, words), the modal state and
// the canonical moves, checked against known answers and against LinuxCNC's own interpreter (rs274 -g) on real
// programs; every error names its line.
#include <gtest/gtest.h>

#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/toolpath/canon_arc.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/gcode/lexer.hpp"
#include "rosmill/gcode/rs274_check.hpp"
#include "test_post_jobs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::gcode;

namespace {

Block lex(const std::string& line) { return lex_line(line, Place{"p.ngc", 7}); }

// The message of the Error `read` throws, or "" when it throws none.
template <class Read>
std::string error_of(Read&& read) {
  try {
    read();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string lex_error(const std::string& line) { return error_of([&] { lex(line); }); }

// The canonical moves of a program, read line by line.
std::vector<CanonMove> moves_of(const std::vector<std::string>& lines) {
  Interpreter reader("p.ngc");
  std::vector<CanonMove> moves;
  for (size_t i = 0; i < lines.size(); ++i)
    if (reader.read(lines[i], i + 1), reader.moved()) moves.push_back(reader.move());
  return moves;
}

std::string read_error(const std::vector<std::string>& lines) { return error_of([&] { moves_of(lines); }); }

}  // namespace

TEST(GcodeLexer, CommentsSpacesAndCase) {
  EXPECT_EQ(code_of("g1 x1 (feed ; not the end) y2 ; z3 (ignored", Place{}), "G1X1Y2");
  EXPECT_EQ(code_of("\tG0 X 1 0\r", Place{}), "G0X10");
  const Block b = lex("n20 g1 x 1 0 (a comment X9) y-.5 f100.");
  EXPECT_EQ(b.get('N'), 20);
  ASSERT_EQ(b.g_count, 1);
  EXPECT_EQ(b.g[0], 10);
  EXPECT_EQ(b.get('X'), 10);  // spaces inside a number are ignored, as in rs274ngc
  EXPECT_EQ(b.get('Y'), -0.5);
  EXPECT_EQ(b.get('F'), 100);
  EXPECT_TRUE(std::isnan(b.get('Z')));
  EXPECT_EQ(lex("X0.1").get('X'), 0.1);  // read exactly, not digit by digit
  EXPECT_TRUE(lex("(only a comment)").empty());
  EXPECT_TRUE(lex("").empty());
}

TEST(GcodeLexer, CodesWithDecimalsAndSeveralCodesPerLine) {
  const Block b = lex("G17 G90.1 G91.1 M3 M8 S1000");
  ASSERT_EQ(b.g_count, 3);
  EXPECT_EQ(b.g[1], 901);
  EXPECT_EQ(b.g[2], 911);
  EXPECT_TRUE(b.has_g(170));
  EXPECT_FALSE(b.has_g(180));
  EXPECT_TRUE(b.has_m(3) && b.has_m(8));
  EXPECT_EQ(g_name(911), "G91.1");
  EXPECT_EQ(g_name(20), "G2");
}

TEST(GcodeLexer, BlockDeleteLineNumbersAndPercentLines) {
  const Block deleted = lex("/N5 G0 X1");
  EXPECT_TRUE(deleted.block_delete);
  EXPECT_EQ(deleted.get('N'), 5);
  EXPECT_FALSE(lex("G0 X1").block_delete);
  EXPECT_TRUE(lex(" % (start)").percent);
  EXPECT_NE(lex_error("%G1 X1").find("alone"), std::string::npos);
  EXPECT_NE(lex_error("G0 /X1").find("block delete"), std::string::npos);
  EXPECT_NE(lex_error("G0 N10 X1").find("line number"), std::string::npos);
}

TEST(GcodeLexer, ErrorsNameTheLineAndWhatIsWrong) {
  const std::pair<const char*, const char*> cases[] = {
      {"G1 X1 (open", "p.ngc:7: comment not closed"},
      {"G1 (a (nested) comment) X1", "p.ngc:7: nested comment"},
      {"G1 X", "p.ngc:7: word X has no number"},
      {"G1 Xinf", "p.ngc:7: word X has no number"},
      {"G1 X1 X2", "p.ngc:7: word X appears twice"},
      {"G1 X#1", "p.ngc:7: unexpected '#' (parameters"},
      {"G1 X[1+2]", "p.ngc:7: unexpected '['"},
      {"N10 G1 X1*57", "p.ngc:7: checksums"},
      {"O100 sub", "p.ngc:7: O-words"},
      {"G1 X1 $", "p.ngc:7: unexpected '$'"},
  };
  for (const auto& [line, message] : cases)
    EXPECT_EQ(lex_error(line).rfind(message, 0), 0u) << line << ": " << lex_error(line);
  try {
    lex_line("G1 X", Place{"", 3});
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "line 3");  // without a file name
  }
}

TEST(GcodeReader, ModalStateFollowsTheProgram) {
  Interpreter r;
  for (const char* line : {"G20 G91 G18 G55 G90.1", "F10 S9000 M4 M7 M8", "T3", "G0 X1"}) r.read(line, 1);
  ModalState s = r.state();
  EXPECT_FALSE(s.metric);
  EXPECT_FALSE(s.absolute);
  EXPECT_TRUE(s.absolute_arc);
  EXPECT_EQ(s.plane, 18);
  EXPECT_EQ(s.work_offset, 55);
  EXPECT_DOUBLE_EQ(s.feed, 254);  // mm/min
  EXPECT_EQ(s.spindle, 4);
  EXPECT_DOUBLE_EQ(s.spindle_rpm, 9000);
  EXPECT_TRUE(s.mist && s.flood);
  EXPECT_EQ(s.selected_tool, 3);
  EXPECT_EQ(s.tool, 0);  // T only selects; M6 loads
  EXPECT_EQ(s.motion, 0);
  EXPECT_FALSE(s.known[0]);  // incremental from an unknown place stays unknown
  r.read("M6 G43", 5);
  EXPECT_EQ(r.state().tool, 3);
  EXPECT_EQ(r.state().length_offset, 3);  // G43 after the change takes the new tool
  r.read("G49 M9 M5", 6);
  EXPECT_EQ(r.state().length_offset, -1);
  EXPECT_FALSE(r.state().mist || r.state().flood);
  r.read("M30", 7);
  s = r.state();
  EXPECT_TRUE(s.ended);
  EXPECT_TRUE(s.absolute);  // a program end resets the modes as LinuxCNC does
  EXPECT_EQ(s.plane, 17);
  EXPECT_EQ(s.work_offset, 54);
  EXPECT_EQ(s.motion, 1);
}

TEST(GcodeReader, CanonicalMovesWithTheirLinesAndKnownAxes) {
  const auto m = moves_of({"%", "G21 G90 G17 (setup)", "G0 Z5", "X1 Y2", "G1 Z-1 F300", "G91 X2", "G90 G0 Z5", "%"});
  ASSERT_EQ(m.size(), 5u);
  EXPECT_EQ(m[0].source, 3u);
  EXPECT_EQ(m[0].known_from, 0);
  EXPECT_EQ(m[0].known_to, 4);  // only z
  EXPECT_TRUE(m[0].rapid);
  EXPECT_EQ(m[1].to, Vec3(1, 2, 5));
  EXPECT_TRUE(m[1].to_known());
  EXPECT_EQ(m[2].feed, 300.0f);
  EXPECT_FALSE(m[2].rapid);
  EXPECT_EQ(m[3].from, Vec3(1, 2, -1));
  EXPECT_EQ(m[3].to, Vec3(3, 2, -1));
  EXPECT_EQ(m[4].feed, 0.0f);
  EXPECT_EQ(m[4].source, 7u);
}

TEST(GcodeReader, ArcsInEveryPlaneByCentreOrRadius) {
  // G17: centre from I J; G90.1: absolute; R: the short way (R > 0) or the long way (R < 0).
  auto m = moves_of({"G0 X10 Y0 Z0", "G3 X0 Y10 I-10 J0 Z-1", "G90.1 G2 X10 Y0 I0 J0", "G91.1 G2 X0 Y-10 R10",
                     "G2 X-10 Y0 R-10"});
  ASSERT_EQ(m.size(), 5u);
  EXPECT_EQ(m[1].shape, MoveShape::ArcCCW);
  EXPECT_EQ(m[1].plane, Plane::XY);
  EXPECT_NEAR(m[1].centre.norm(), 0, 1e-12);
  EXPECT_NEAR(arc_sweep(m[1]), M_PI / 2, 1e-12);
  EXPECT_NEAR(m[2].centre.norm(), 0, 1e-12);
  EXPECT_NEAR(m[3].centre.norm(), 0, 1e-9);
  EXPECT_NEAR((m[4].centre - Vec2(-10, -10)).norm(), 0, 1e-9);  // the long way round, the other centre
  // G18: the plane's axes are Z then X (offsets K, I); G19: Y then Z (J, K); the third axis is the helix's.
  m = moves_of({"G0 X0 Y0 Z0", "G18 G2 X10 Z0 I5 K0 Y3", "G19 G3 Y3 Z-4 J0 K-2"});
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[1].plane, Plane::ZX);
  EXPECT_NEAR((m[1].centre - Vec2(0, 5)).norm(), 0, 1e-12);  // (z, x)
  EXPECT_EQ(m[1].to, Vec3(10, 3, 0));
  EXPECT_EQ(m[2].plane, Plane::YZ);
  EXPECT_NEAR((m[2].centre - Vec2(3, -2)).norm(), 0, 1e-12);  // (y, z)
  // Inches: ends, offsets and radii are all scaled.
  m = moves_of({"G20 G0 X0 Y0 Z0", "G2 X1 Y0 I0.5 J0 P2"});
  EXPECT_NEAR((m[1].centre - Vec2(12.7, 0)).norm(), 0, 1e-12);
  EXPECT_EQ(m[1].turns, 2);
}

TEST(GcodeReader, WhatTheReaderCannotFollowLeavesAxesUnknown) {
  Interpreter r;
  for (const char* line : {"G0 X1 Y2 Z3", "G92 X0", "G1 X1 F100"}) r.read(line, 1);
  EXPECT_EQ(r.move().from.x(), 0);  // G92: the current point takes the coordinates given
  EXPECT_TRUE(r.move().from_known());
  r.read("G28", 4);
  EXPECT_FALSE(r.moved());
  EXPECT_FALSE(r.state().known[0] || r.state().known[1] || r.state().known[2]);
  r.read("G0 X0 Y0 Z0", 5);
  r.read("G53 G0 Z-10", 6);
  EXPECT_FALSE(r.moved());  // a move in machine coordinates: no program position
  EXPECT_TRUE(r.state().known[0] && r.state().known[1]);
  EXPECT_FALSE(r.state().known[2]);
}

TEST(GcodeReader, ErrorsNameTheLineAndWhatIsWrong) {
  const std::pair<std::vector<std::string>, const char*> cases[] = {
      {{"G0 X0", "X1 G0 G1"}, "p.ngc:2: G0 and G1 in one line"},
      {{"G0 X0", "G17 G18"}, "p.ngc:2: G17 and G18 in one line"},
      {{"G0 X0", "", "G12 X1"}, "p.ngc:3: G12 is not an RS274/NGC G code"},
      {{"G81 X0 Y0 Z-1 R1"}, "p.ngc:1: G81 is not followed"},
      {{"X1"}, "p.ngc:1: axis words without a motion mode"},
      {{"G0 Z5", "G2 X1 Y0 I1"}, "p.ngc:2: an arc cannot be the first move"},
      {{"G0 X0 Y0 Z0", "G2 X10 Y0 I3"}, "p.ngc:2: radius to the end of the arc differs"},
      {{"G0 X0 Y0 Z0", "G2 X10 Y0"}, "p.ngc:2: arc without I/J/K or R"},
      {{"G0 X0 Y0 Z0", "G2 X10 Y0 R5 I5"}, "p.ngc:2: arc with both R and I/J/K"},
      {{"G0 X0 Y0 Z0", "G2 X10 Y0 R4"}, "p.ngc:2: arc radius R is smaller than half the chord"},
      {{"G0 X0 Y0 Z0", "G2 X0 Y0 R4"}, "p.ngc:2: a full circle cannot be given with R"},
      {{"G0 X0 Y0 Z0", "G2 X0 Y0 I1 K1"}, "p.ngc:2: K is not allowed for an arc in the G17 plane"},
      {{"G0 X0 Y0 Z0", "G2 X0 Y0 I1 P1.5"}, "p.ngc:2: the turns P"},
      {{"G0 X0 Y0 Z0", "G3"}, "p.ngc:2: G3 without an end point"},
  };
  for (const auto& [lines, message] : cases)
    EXPECT_EQ(read_error(lines).rfind(message, 0), 0u) << message << " <- " << read_error(lines);
}

TEST(GcodeReader, ThePercentLinesDemarcateTheProgram) {
  Interpreter r;
  r.read("%", 1);
  EXPECT_FALSE(r.state().ended);
  r.read("G0 X1", 2);
  r.read("%", 3);
  EXPECT_TRUE(r.state().ended);
  Interpreter late;
  late.read("G0 X1", 1);
  late.read("%", 2);  // a '%' after blocks closes the program
  EXPECT_TRUE(late.state().ended);
}

TEST(GcodeReader, StateBeforeALine) {
  const std::vector<std::string> p = {"G21 G90", "T2 M6", "G0 X1 Y2 Z3", "S5000 M3", "G1 Z-1 F200", "M30"};
  const ModalState s = state_before(p, 4);  // before line 5
  EXPECT_EQ(s.tool, 2);
  EXPECT_EQ(s.spindle, 3);
  EXPECT_EQ(s.motion, 0);
  EXPECT_EQ(s.position, Vec3(1, 2, 3));
  EXPECT_DOUBLE_EQ(s.feed, 0);
  EXPECT_DOUBLE_EQ(state_before(p, 5).feed, 200);
}

// The reader's canonical moves are LinuxCNC's: one per motion line, the same ends, centres, directions and feeds.
void expect_same_as_rs274(const std::vector<std::string>& lines, const std::string& what) {
  const Rs274Result r = run_rs274(lines);
  ASSERT_TRUE(r.ok) << what << ": " << r.error;
  const std::vector<CanonMove> ours = moves_of(lines);
  ASSERT_EQ(ours.size(), r.moves.size()) << what;
  for (size_t k = 0; k < ours.size(); ++k) {
    const std::string at = what + ", line " + std::to_string(ours[k].source);
    EXPECT_LT((ours[k].to - r.moves[k].to).cwiseAbs().maxCoeff(), 1e-3) << at;
    EXPECT_EQ(ours[k].rapid, r.moves[k].rapid) << at;
    ASSERT_EQ(ours[k].shape, r.moves[k].shape) << at;
    if (!ours[k].rapid) {
      EXPECT_NEAR(ours[k].feed, r.moves[k].feed, 1e-2) << at;
    }
    if (ours[k].is_arc()) {
      EXPECT_EQ(ours[k].plane, r.moves[k].plane) << at;
      EXPECT_EQ(ours[k].turns, r.moves[k].turns) << at;
      EXPECT_LT((ours[k].centre - r.moves[k].centre).cwiseAbs().maxCoeff(), 1e-3) << at;
    }
  }
}

TEST(GcodeReader, KnownAnswersFromLinuxCncOnRealPrograms) {
  for (const char* dialect : {"linuxcnc", "grbl"})
    for (bool arcs : {false, true}) {
      PostOptions o;
      o.dialect = dialect;
      o.arcs = arcs;
      o.line_numbers = arcs;
      const Program p = post(Job{test::raster_toolpath(), test::cylinder_contours(), test::dome_contours()}, o);
      expect_same_as_rs274(p.lines, std::string(dialect) + (arcs ? " arcs" : ""));
    }
  // Hand-written: inches, incremental moves, arcs by radius, absolute centres, helices and turns, other planes.
  expect_same_as_rs274({"%", "G20 G17 G90 (inch)", "G0 X0 Y0 Z1", "G1 Z-0.1 F20", "G2 X1 Y0 R0.6",
                        "G91 G1 X0.5 Y0.25 ; incremental", "G90 G90.1 G3 X1.5 Y1.25 I1.5 J0.75 Z-0.2",
                        "G91.1 G2 X1.5 Y1.25 I0 J-0.5 P2", "G21 G0 Z20", "G18 G0 X0 Y0 Z0", "G2 X10 Z0 I5 K0 Y3 F500",
                        "G19 G3 Y-3 Z-4 J-3 K-2", "G17 G0 Z20", "M30", "%"},
                       "hand-written");
}
