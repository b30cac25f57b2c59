// Machine limits: config/machine.yaml is read and validated; programs breaking a limit are refused with the line
// and the limit; the modal state a resume restores is computed by scanning the program.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "rosmill/error.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/gcode/lexer.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/post.hpp"
#include "test_post_jobs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::gcode;

namespace {

MachineLimits bundled_machine() { return load_machine_limits(ROSMILL_SOURCE_DIR "/config/machine.yaml"); }

std::vector<std::string> program(std::initializer_list<std::string> body) {
  std::vector<std::string> l = {"G17 G21 G90 G54", "G0 Z10", "X0 Y0", "S10000 M3"};
  l.insert(l.end(), body);
  l.push_back("M30");
  return l;
}

std::string write_yaml(const std::string& text) {
  const std::string path = ::testing::TempDir() + "/machine_test.yaml";
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(MachineLimits, ReadsTheBundledMachine) {
  const MachineLimits m = bundled_machine();
  EXPECT_EQ(m.name, "linuxcnc-sim-mm");
  EXPECT_DOUBLE_EQ(m.envelope.min.x(), -254);
  EXPECT_DOUBLE_EQ(m.envelope.max.z(), 101.6);
  EXPECT_DOUBLE_EQ(m.max_feed, 1828);
  EXPECT_DOUBLE_EQ(m.table_z, -50);
}

TEST(MachineLimits, BadFilesNameTheField) {
  auto expect_error = [](const std::string& yaml, const std::string& needle) {
    try {
      load_machine_limits(write_yaml(yaml));
      ADD_FAILURE() << "accepted: " << yaml;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  const std::string env = "envelope: {x: [0, 100], y: [0, 100], z: [-10, 50]}\n";
  expect_error("name: m\n", "envelope");
  expect_error("envelope: {x: [0, 100], y: [0], z: [-10, 50]}\n", "envelope.y");
  expect_error("envelope: {x: [100, 0], y: [0, 100], z: [-10, 50]}\n", "min must be below max");
  expect_error(env + "table_z: -5\nmax_feed: -3\nmax_spindle_rpm: 1\nclearance_over_stock: 1\n", "max_feed");
  expect_error(env + "table_z: -50\nmax_feed: 3\nmax_spindle_rpm: 1\nclearance_over_stock: 1\n", "table_z");
  expect_error(env + "table_z: -5\nmax_feed: 3\nmax_spindle_rpm: x\nclearance_over_stock: 1\n", "max_spindle_rpm");
  expect_error("[1, 2", "not valid YAML");
  EXPECT_THROW(load_machine_limits("/nonexistent/machine.yaml"), Error);
}

TEST(MachineLimits, PostedJobsPassAndEachBrokenLimitIsNamed) {
  const MachineLimits m = bundled_machine();
  for (const Toolpath& tp : {test::raster_toolpath(), test::cylinder_contours(), test::dome_contours()}) {
    PostOptions o;
    o.arcs = true;
    o.arc_tolerance = 0.1;
    const Program ok = post(Job{tp}, o);
    const auto v = check_limits(ok.lines, m);
    EXPECT_TRUE(v.empty()) << tp.strategy << ": " << v.front().message();
    EXPECT_NO_THROW(require_within_limits(ok.lines, m));
  }

  struct Case {
    std::vector<std::string> lines;
    size_t line;
    std::string limit;
  };
  const std::vector<Case> cases = {
      {program({"G0 X300", "G1 Z-1 F100"}), 5, "envelope x max"},
      {program({"G0 Y-260", "G1 Z-1 F100"}), 5, "envelope y min"},
      {program({"G1 Z-60 F100"}), 5, "envelope z min"},
      {program({"G1 Z-1 F5000"}), 5, "max feed"},
      {program({"S30000 M3", "G1 Z-1 F100"}), 5, "max spindle speed"},
      {program({"G1 Z-1 F100", "X5", "G0 X20"}), 7, "rapid clearance"},  // sideways rapid inside the stock
      {program({"G1 Z-1 F100", "X5", "G0 Z0", "G0 Z5"}), 7, "rapid clearance"},  // rapid down to 1 mm over the cut
      // An arc whose end points are inside but whose sweep leaves the envelope.
      {program({"G0 X245 Y0", "G1 Z-1 F100", "G3 X245 Y20 I0 J10"}), 7, "envelope x max"},
      // What the checker cannot follow is refused, not passed: stored and machine positions, offset changes,
      // other work offsets.
      {program({"G1 Z-1 F100", "G28"}), 6, "unchecked move"},
      {program({"G53 G2 X0 Y0 I1"}), 5, "unchecked move"},  // G53 is followed with G0 or G1 and X, Y, Z alone
      {program({"G53 G0 Z-60"}), 5, "envelope z min"},       // ... in machine coordinates
      {program({"G92 X0 Y0", "G1 Z-1 F100"}), 5, "unchecked move"},
      {program({"G10 L2 P1 Z-500", "G1 Z-1 F100"}), 5, "unchecked move"},
      {program({"G55", "G1 Z-1 F100"}), 5, "work offset"},
      // An arc by radius and a full circle (end = start) are swept as the controller sweeps them.
      {program({"G0 X245 Y0", "G1 Z-1 F100", "G3 X245 Y20 R10"}), 7, "envelope x max"},
      {program({"G0 X245 Y0", "G1 Z-1 F100", "G3 X245 Y0 I5 J0"}), 7, "envelope x max"},
      // Violations come by line: the feed on line 5 before the envelope on line 7.
      {program({"G1 Z-1 F5000", "X5", "G0 Z10 X400"}), 5, "max feed"},
  };
  for (const Case& c : cases) {
    const auto v = check_limits(c.lines, m);
    ASSERT_FALSE(v.empty()) << c.limit;
    EXPECT_EQ(v.front().line, c.line) << c.limit << ": " << v.front().message();
    EXPECT_EQ(v.front().limit, c.limit) << v.front().message();
    try {
      require_within_limits(c.lines, m);
      ADD_FAILURE() << "not refused: " << c.limit;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), "line " + std::to_string(c.line));
      EXPECT_NE(std::string(e.what()).find(c.limit), std::string::npos) << e.what();
    }
  }
  // Below the table with a work offset: the program's z -20 is machine z -60.
  MachineLimits shifted = m;
  shifted.envelope.min.z() = -100;
  shifted.work_offset.origin = Vec3(0, 0, -40);
  const auto v = check_limits(program({"G1 Z-20 F100"}), shifted);
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v.front().limit, "table");
  // With the stock top given, a rapid at 1 mm over the highest cut is still refused when the stock is higher.
  LimitCheckOptions o;
  o.stock_top = 5;
  EXPECT_FALSE(check_limits(program({"G1 Z-1 F100", "X5", "G0 Z6"}), m, o).empty());
  EXPECT_TRUE(check_limits(program({"G1 Z-1 F100", "X5", "G0 Z7"}), m, o).empty());
}

TEST(MachineLimits, WhatTheCheckCannotFollowIsRefusedWithTheLine) {
  const MachineLimits m = bundled_machine();
  auto error_of = [&](std::initializer_list<std::string> body) {
    try {
      check_limits(program(body), m);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_of({"G1 Z-1 F100", "G18 G2 X10 Z-1 I5 K0"}),
            "line 6: arcs outside the XY plane (G17) are not followed");
  EXPECT_EQ(error_of({"G1 X0 Y0 Z-1 F100", "G93 G1 X5"}),
            "line 6: a feed move under inverse time (G93) without its F word");
  // Followed: an inverse-time move's feed is its F (1/min) times its length, against the machine's.
  const std::vector<LimitViolation> fast = check_limits(program({"G1 X0 Y0 Z-1 F100", "G93 G1 X100 F100"}), m);
  ASSERT_EQ(fast.size(), 1u);
  EXPECT_EQ(fast.front().limit, "max feed");
  EXPECT_NE(fast.front().detail.find("F10000 "), std::string::npos) << fast.front().detail;
  EXPECT_TRUE(check_limits(program({"G1 X0 Y0 Z-1 F100", "G93 G1 X100 F5"}), m).empty());
  EXPECT_EQ(error_of({"G1 Z-1 F100", "G2 X10 Y0 I3"}).rfind("line 6: radius to the end of the arc differs", 0), 0u);
  EXPECT_EQ(error_of({"G1 Z-1 F100 (open"}), "line 5: comment not closed with ')'");
  EXPECT_EQ(error_of({"G81 X0 Y0 Z-1 R1"}).rfind("line 5: G81 is not followed", 0), 0u);
}

TEST(ModalScan, StateBeforeALineIsWhatTheControllerHas) {
  PostOptions o;
  o.arcs = true;
  const Program p = post(Job{test::raster_toolpath(), test::revolution_contours(
                                                          "c", [](double) { return 20.0; }, 10, 5, 720)},
                         o);
  size_t arc_line = 0;
  for (size_t i = 0; i < p.lines.size(); ++i)
    if (p.lines[i].rfind("G3", 0) == 0) arc_line = i;
  ASSERT_GT(arc_line, 0u);
  const ModalState s = state_before(p.lines, arc_line + 1);
  EXPECT_TRUE(s.metric);
  EXPECT_TRUE(s.absolute);
  EXPECT_EQ(s.plane, 17);
  EXPECT_EQ(s.work_offset, 54);
  EXPECT_EQ(s.motion, 3);
  EXPECT_EQ(s.tool, 2);
  EXPECT_EQ(s.length_offset, 2);
  EXPECT_EQ(s.spindle, 3);
  EXPECT_DOUBLE_EQ(s.spindle_rpm, 12000);
  EXPECT_TRUE(s.flood);
  EXPECT_DOUBLE_EQ(s.feed, 800);
  EXPECT_NEAR(s.position.head<2>().norm(), 23.0, 1e-3);
  EXPECT_TRUE(s.known[0] && s.known[1] && s.known[2]);
  EXPECT_THROW(lex_line("G1 X(unclosed", Place{"", 3}), Error);
  EXPECT_THROW(lex_line("G1 X", Place{"", 3}), Error);
  const Block b = lex_line("n20 g1 x-1.5 ( comment X9 ) y2 ; z7", Place{});
  EXPECT_DOUBLE_EQ(b.get('X'), -1.5);
  EXPECT_TRUE(std::isnan(b.get('Z')));
  EXPECT_DOUBLE_EQ(b.get('N'), 20);
  // Packed words (as GRBL senders strip spaces): "0X9" is G0 then X9, not a hexadecimal number.
  const Block packed = lex_line("G0X9Y-.5Z1.", Place{});
  ASSERT_EQ(packed.g_count, 1);
  EXPECT_EQ(packed.g[0], 0);
  EXPECT_DOUBLE_EQ(packed.get('X'), 9);
  EXPECT_DOUBLE_EQ(packed.get('Y'), -0.5);
  EXPECT_DOUBLE_EQ(packed.get('Z'), 1);
  EXPECT_THROW(lex_line("G1 Xinf", Place{}), Error);
}
