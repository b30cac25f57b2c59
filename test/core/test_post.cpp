// The post-processor: dialect words, modal output, number format and the line-to-toolpath map.
#include <gtest/gtest.h>

#include <regex>
#include <set>

#include "rosmill/error.hpp"
#include "rosmill/gcode/number_format.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"

#include <nlohmann/json.hpp>
#include "test_post_jobs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::gcode;

namespace {
bool has_line(const Program& p, const std::string& text) {
  for (const auto& l : p.lines)
    if (l == text) return true;
  return false;
}
size_t index_of(const Program& p, const std::string& text) {
  for (size_t i = 0; i < p.lines.size(); ++i)
    if (p.lines[i] == text) return i;
  return p.lines.size();
}
}  // namespace

TEST(PostNumbers, FixedPrecisionWithoutNegativeZero) {
  auto word = [](double v, int d) {
    std::string s;
    append_word(s, 'X', v, d);
    return s;
  };
  EXPECT_EQ(word(-0.0001, 3), "X0");
  EXPECT_EQ(word(-0.0004999, 3), "X0");
  EXPECT_EQ(word(-0.0005, 3), "X-0.001");
  EXPECT_EQ(word(12.5, 3), "X12.5");
  EXPECT_EQ(word(100, 3), "X100");
  EXPECT_EQ(word(-3.14159, 4), "X-3.1416");
  EXPECT_EQ(word(0.05, 1), "X0.1");
  EXPECT_EQ(word(7.0000004, 6), "X7");
  EXPECT_THROW(decimal_scale(9), Error);
}

TEST(PostLinuxcnc, HeaderToolSpindleCoolantAndEnd) {
  Job job{test::raster_toolpath()};
  const Program p = post(job, PostOptions{});
  EXPECT_TRUE(has_line(p, "G17 G21 G40 G49 G54 G80 G90 G94"));
  EXPECT_TRUE(has_line(p, "G64 P0.01"));
  const size_t m6 = index_of(p, "T1 M6"), g43 = index_of(p, "G43 H1"), s = index_of(p, "S12000 M3"),
               m8 = index_of(p, "M8");
  ASSERT_LT(m8, p.lines.size());
  EXPECT_LT(m6, g43);
  EXPECT_LT(g43, s);
  EXPECT_LT(s, m8);
  // The first move after the length offset goes straight up to the clearance height.
  EXPECT_EQ(p.lines[g43 + 1], "G0 Z10");
  EXPECT_EQ(p.lines.back(), "M30");
  EXPECT_EQ(p.lines[p.lines.size() - 3], "M5");
  EXPECT_EQ(p.lines[p.lines.size() - 2], "M9");
}

TEST(PostGrbl, PauseForToolChangeAndShortLines) {
  Job job{test::raster_toolpath(), test::cylinder_contours()};
  PostOptions o;
  o.dialect = "grbl";
  const Program p = post(job, o);
  for (const auto& l : p.lines) {
    EXPECT_LE(l.size(), 80u) << l;
    EXPECT_EQ(l.find("M6"), std::string::npos) << l;
    EXPECT_EQ(l.find("G64"), std::string::npos) << l;
    EXPECT_EQ(l.find("G43"), std::string::npos) << l;
  }
  size_t pauses = 0;
  for (size_t i = 0; i < p.lines.size(); ++i)
    if (p.lines[i] == "M0") {
      ++pauses;
      ASSERT_GT(i, 0u);
      EXPECT_NE(p.lines[i - 1].find("(load tool T"), std::string::npos) << p.lines[i - 1];
    }
  EXPECT_EQ(pauses, 2u);
  // Between tools: the spindle and coolant stop before the pause.
  const size_t second = index_of(p, "(load tool T2 flat D6 test, set its length, then cycle start)");
  ASSERT_LT(second, p.lines.size());
  EXPECT_EQ(p.lines[second - 3], "M5");
  EXPECT_EQ(p.lines[second - 2], "M9");
}

TEST(PostModal, WordsNotRepeatedAndNoNegativeZero) {
  Job job{test::cylinder_contours()};
  const Program p = post(job, PostOptions{});
  const std::regex word("([GXYZF])(-?[0-9.]+)");
  std::string last_g, last_f;
  for (const auto& l : p.lines) {
    if (l.empty() || l[0] == '(') continue;
    if (l.rfind("G43", 0) == 0) last_g.clear();  // after a length offset every word is written again
    EXPECT_EQ(l.find("-0 "), std::string::npos) << l;
    EXPECT_FALSE(l.size() >= 2 && l.compare(l.size() - 2, 2, "-0") == 0) << l;
    for (auto it = std::sregex_iterator(l.begin(), l.end(), word); it != std::sregex_iterator(); ++it) {
      const std::string letter = (*it)[1], value = (*it)[2];
      if (letter == "G" && (value == "0" || value == "1" || value == "2" || value == "3")) {
        EXPECT_NE(value, last_g) << "motion word repeated: " << l;
        last_g = value;
      }
      if (letter == "F") {
        EXPECT_NE(value, last_f) << "feed repeated: " << l;
        last_f = value;
      }
    }
  }
  // One line per circle point: 36 feed moves per contour, written as G1 lines.
  size_t feed_lines = 0;
  for (const LineOrigin& o : p.origin) feed_lines += o.first_move >= 2;
  EXPECT_EQ(feed_lines, 12u * (36 + 1));
}

TEST(PostMap, EveryMoveLineLeadsBackToItsMove) {
  Job job{test::raster_toolpath(), test::cone_contours()};
  const Program p = post(job, PostOptions{});
  ASSERT_EQ(p.lines.size(), p.origin.size());
  std::set<std::tuple<int, int, int>> seen;
  for (size_t i = 0; i < p.lines.size(); ++i) {
    const LineOrigin& o = p.origin[i];
    if (o.first_move < 0) continue;
    ASSERT_EQ(o.first_move, o.last_move);
    const Move& m = job[o.toolpath].passes[o.pass].moves[o.first_move];
    if (m.type == MoveType::Rapid) {
      EXPECT_EQ(p.lines[i].find("G1"), std::string::npos) << p.lines[i];
    }
    EXPECT_TRUE(seen.insert({o.toolpath, o.pass, o.first_move}).second) << "move posted twice";
  }
  size_t total = 0;
  for (const auto& tp : job) total += tp.move_count();
  // Only zero-length moves (the rapid back above the raster's last point is not one) may be absent.
  EXPECT_GE(seen.size(), total - 2 * job[1].passes.size());
}

TEST(PostOptions, LineNumbersAndUnknownDialect) {
  Job job{test::raster_toolpath()};
  PostOptions o;
  o.line_numbers = true;
  o.line_number_step = 5;
  const Program p = post(job, o);
  for (size_t i = 0; i < p.lines.size(); ++i) EXPECT_EQ(p.lines[i].rfind("N" + std::to_string(10 + 5 * i) + " ", 0), 0u);
  o.dialect = "fanuc-ish";
  try {
    post(job, o);
    FAIL() << "unknown dialect accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("known: linuxcnc, grbl"), std::string::npos) << e.what();
  }
  EXPECT_THROW(post(Job{}, PostOptions{}), Error);
}

// The output's rounding stays within a tenth of the plan's tolerance: the decimals follow the toolpaths' tolerance
// (a point rounded on three axes moves sqrt(3)/2 units of the last digit), at least 3 and at most 6.
TEST(Post, DecimalsKeepRoundingWithinATenthOfTheTolerance) {
  for (double tol : {1.0, 0.05, 0.01, 0.005, 0.001, 0.0001, 1e-5, 1e-7}) {
    const int d = gcode::decimals_for_tolerance(tol);
    SCOPED_TRACE(tol);
    EXPECT_GE(d, 3);
    EXPECT_LE(d, 6);
    if (d < 6) {
      EXPECT_LE(std::sqrt(3.0) / 2 * std::pow(10.0, -d), tol / 10 + 1e-15);
    }
    if (d > 3) {
      EXPECT_GT(std::sqrt(3.0) / 2 * std::pow(10.0, -(d - 1)), tol / 10);  // the fewest that do
    }
  }
  EXPECT_EQ(gcode::decimals_for_tolerance(0.001), 4);
  EXPECT_EQ(gcode::decimals_for_tolerance(0.01), 3);
  EXPECT_EQ(gcode::decimals_for_tolerance(NAN), 3);
  // A job whose toolpaths carry 0.001 mm: every written point within 0.0001 mm of the toolpath's.
  Job job{test::raster_toolpath()};
  for (Move& m : job[0].passes[0].moves) m.to += Vec3(1.0 / 3, 2.0 / 7, 1.0 / 9);
  job[0].tolerance = 0.001;
  const gcode::Program p = gcode::post(job);
  EXPECT_EQ(p.decimals, 4);
  EXPECT_TRUE(std::regex_search(p.text(), std::regex("X-?[0-9]+\\.[0-9]{4}\\b")));
  EXPECT_FALSE(std::regex_search(p.text(), std::regex("X-?[0-9]+\\.[0-9]{5}")));
  job[0].tolerance = NAN;  // unknown: the customary 3
  EXPECT_EQ(gcode::post(job).decimals, 3);
  gcode::PostOptions five;
  five.decimals = 5;  // as asked
  EXPECT_EQ(gcode::post(job, five).decimals, 5);
}

// A toolpath file keeps the plan's tolerance (so `rosmill post` of a file rounds as the plan allows); an older
// file without it reads as unknown; a bad one is refused naming the field.
TEST(Post, ToolpathFilesCarryTheTolerance) {
  Toolpath tp = test::raster_toolpath();
  tp.tolerance = 0.002;
  EXPECT_DOUBLE_EQ(toolpath_from_json(toolpath_to_json(tp), "t").tolerance, 0.002);
  nlohmann::json j = toolpath_to_json(tp);
  j.erase("tolerance");
  EXPECT_TRUE(std::isnan(toolpath_from_json(j, "t").tolerance));
  j["tolerance"] = -1;
  try {
    toolpath_from_json(j, "file.json: toolpath 0");
    ADD_FAILURE() << "a negative tolerance was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("file.json: toolpath 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'tolerance'"), std::string::npos) << e.what();
  }
}
