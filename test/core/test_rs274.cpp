// LinuxCNC's own interpreter (rs274 -g) judges the programs: accepted without error, and its canonical moves are
// the toolpath's moves within the output precision. Runs over synthetic jobs in every dialect and option, and
// over every strategy, preset and template (plan_names.hpp) on every seed primitive (one test case each).
#include <gtest/gtest.h>

#include "rosmill/testing/sanitized.hpp"

#include <algorithm>

#include "rosmill/control/controller.hpp"
#include "plan_names.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/gcode/lexer.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/gcode/rs274_check.hpp"
#include "test_post_jobs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::gcode;

namespace {

void expect_verified(const Job& job, const PostOptions& o, const std::string& what) {
  const Program p = post(job, o);
  const Rs274Result r = run_rs274(p.lines);
  ASSERT_TRUE(r.ok) << what << ": " << r.error;
  const VerifyReport rep = compare_with_job(p, job, r, o.arc_tolerance);
  EXPECT_TRUE(rep.ok) << what << ": " << rep.problem;
  EXPECT_GT(rep.canon_moves, 0u);
  EXPECT_LE(rep.max_deviation, o.arc_tolerance + 0.001) << what;
}

}  // namespace

TEST(Rs274Verify, SyntheticJobsInEveryDialect) {
  const Job job{test::raster_toolpath(), test::cylinder_contours(), test::cone_contours(),
                test::revolution_contours("dome", [](double z) { return std::sqrt(std::max(0.0, 2500 - z * z)); },
                                          50, 5, 180, 3)};
  for (const Dialect& d : dialects())
    for (bool arcs : {false, true})
      for (bool numbers : {false, true}) {
        PostOptions o;
        o.dialect = d.name;
        o.arcs = arcs;
        o.line_numbers = numbers;
        o.arc_tolerance = 0.01;
        expect_verified(job, o, d.name + (arcs ? " arcs" : "") + (numbers ? " N" : ""));
      }
}

TEST(Rs274Verify, ArcsAreReadAsArcsWithTheirCentres) {
  const Job job{test::revolution_contours("cylinder", [](double) { return 25.0; }, 10, 5, 720)};
  PostOptions o;
  o.arcs = true;
  const Program p = post(job, o);
  const Rs274Result r = run_rs274(p.lines);
  ASSERT_TRUE(r.ok) << r.error;
  size_t arcs = 0;
  for (const CanonMove& m : r.moves)
    if (m.is_arc()) {
      ++arcs;
      EXPECT_NEAR(m.centre.norm(), 0.0, 1e-3);
      EXPECT_NEAR(m.to.head<2>().norm(), 28.0, 1e-3);
      EXPECT_EQ(m.shape, MoveShape::ArcCCW);  // the contours run counter-clockwise
      EXPECT_EQ(m.turns, 1);
    }
  EXPECT_GE(arcs, 2u);
}

TEST(Rs274Verify, BrokenProgramIsReportedWithTheBlock) {
  const Rs274Result r = run_rs274({"G21 G90", "G0 X1", "G1 X5", "M30"});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("zero feed rate"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("G1 X5"), std::string::npos) << r.error;
  // A wrong point is caught by the comparison.
  Job job{test::raster_toolpath()};
  Program p = post(job, PostOptions{});
  for (auto& l : p.lines)
    if (l == "X40") {
      l = "X40.01";
      break;
    }
  const VerifyReport rep = compare_with_job(p, job, run_rs274(p.lines), 0.005);
  EXPECT_FALSE(rep.ok);
  EXPECT_NE(rep.problem.find("from the toolpath point"), std::string::npos) << rep.problem;
}

// One case per seed primitive, so that ctest runs them side by side.
class EveryStrategyOnSeedPrimitive : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryStrategyOnSeedPrimitive, AcceptedByRs274WithTheToolpathsMoves) {
  const std::string& name = GetParam();
  const std::vector<std::string> primitives = primitive_names();
  const size_t index = static_cast<size_t>(std::find(primitives.begin(), primitives.end(), name) - primitives.begin());
  const Mesh mesh = make_primitive(name);
  PointCloud cloud;
  cloud.points = mesh.vertices;
  cloud.recompute_bbox();
  const std::vector<test::PlanName> names = test::plan_names();
  size_t verified = 0, expected = 0;
  for (size_t i = 0; i < names.size(); ++i) {
    const test::PlanName& s = names[i];
    // Under the sanitizers each name runs on one primitive, in turn (the paths are the same code on all five;
    // on all five the test alone took half the sanitizer stage's budget); adaptive clearing on the cube, its
    // quickest. Adaptive clearing never runs on the cavity: its narrow groove gives a program of 65,000 moves
    // that took this test from 10 to 110 s (six minutes under the sanitizers) and reaches no code the other four
    // do not (test_adaptive clears a slot barely wider than the tool and checks it).
    const bool adaptive = s.name.find("adaptive") != std::string::npos;
    const size_t turn = adaptive ? 0 : i % primitives.size();
    if (rosmill::testing::kSanitized && turn != index) continue;
    if (adaptive && name == "cavity") continue;
    expected += 2;
    PlanParams params;
    // Contour machining offsets by a flat end mill's radius; the other strategies take a ball.
    params.tool.cutter = s.name == "contour" ? Cutter::flat(6) : Cutter::ball(6);
    params.tool.stepover = 3;
    params.tool.stepdown = 5;
    params.tolerance = 0.05;
    Job job;
    try {
      job = test::plan_named(s, mesh, cloud, params);
    } catch (const Error& e) {
      ADD_FAILURE() << s.name << " on " << name << ": " << e.what();
      continue;
    }
    for (bool arcs : {false, true}) {
      PostOptions o;
      o.arcs = arcs;
      if (s.multi_axis) o = test::multi_axis_post(o);  // every move a line: arcs or not, the same program
      expect_verified(job, o, s.name + " on " + name + (arcs ? " with arcs" : ""));
      ++verified;
    }
  }
  EXPECT_EQ(verified, expected);
}

INSTANTIATE_TEST_SUITE_P(SeedPrimitives, EveryStrategyOnSeedPrimitive, ::testing::ValuesIn(primitive_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

namespace {

// rs274's moves of a program that come from its lines [first_line, end), 1-based: the moves of earlier lines
// (one per line with axis words) are skipped.
std::vector<CanonMove> moves_from(const std::vector<std::string>& lines, const Rs274Result& r, size_t first_line) {
  size_t skip = 0;
  for (size_t i = 0; i + 1 < first_line; ++i) {
    const Block b = lex_line(lines[i], Place{});
    skip += b.has('X') || b.has('Y') || b.has('Z');
  }
  return std::vector<CanonMove>(r.moves.begin() + static_cast<std::ptrdiff_t>(std::min(skip, r.moves.size())), r.moves.end());
}

}  // namespace

TEST(Rs274Verify, AResumedProgramMovesAsTheOriginalFromItsLine) {
  // Two tools, arcs: a resume at any line must restore tool, length offset, spindle, feed, motion mode and place.
  const Job job{test::raster_toolpath(30, 10, 2.5), test::revolution_contours("c", [](double) { return 12.0; }, 10, 5, 360)};
  for (const char* dialect : {"linuxcnc", "grbl"}) {
    PostOptions o;
    o.dialect = dialect;
    o.arcs = true;
    const Program p = post(job, o);
    const Rs274Result whole = run_rs274(p.lines);
    ASSERT_TRUE(whole.ok) << whole.error;
    size_t resumes = 0;
    for (size_t line = 2; line <= p.lines.size(); line += 5) {
      control::SendOptions so;
      so.from_line = line;
      const std::vector<std::string> resumed = control::resumed_program(p.lines, so, dialect);
      const size_t preamble = resumed.size() - (p.lines.size() - line + 1);
      const Rs274Result r = run_rs274(resumed);
      ASSERT_TRUE(r.ok) << dialect << " from line " << line << ": " << r.error;
      const std::vector<CanonMove> expected = moves_from(p.lines, whole, line), got = moves_from(resumed, r, preamble + 1);
      ASSERT_EQ(got.size(), expected.size()) << dialect << " from line " << line;
      for (size_t k = 0; k < got.size(); ++k) {
        const std::string at = std::string(dialect) + " from line " + std::to_string(line) + ", move " + std::to_string(k);
        ASSERT_EQ(got[k].rapid, expected[k].rapid) << at;
        ASSERT_EQ(got[k].shape, expected[k].shape) << at;
        EXPECT_LT((got[k].to - expected[k].to).cwiseAbs().maxCoeff(), 1e-4) << at;
        EXPECT_NEAR(got[k].feed, expected[k].feed, 1e-6) << at;
        if (got[k].is_arc()) {
          EXPECT_LT((got[k].centre - expected[k].centre).cwiseAbs().maxCoeff(), 1e-4) << at;
          EXPECT_EQ(got[k].turns, expected[k].turns) << at;
        }
      }
      // The preamble ends where the original was before the line, with the same modal state.
      const ModalState before = state_before(p.lines, line - 1), restored = state_before(resumed, preamble);
      if (before.known[0] && before.known[1] && before.known[2]) {
        EXPECT_LT((restored.position - before.position).cwiseAbs().maxCoeff(), 1e-4) << dialect << " line " << line;
      }
      EXPECT_EQ(restored.tool, before.tool) << line;
      EXPECT_EQ(restored.length_offset, before.length_offset) << line;
      EXPECT_EQ(restored.spindle, before.spindle) << line;
      if (before.spindle != 5) {
        EXPECT_DOUBLE_EQ(restored.spindle_rpm, before.spindle_rpm) << line;
      }
      EXPECT_EQ(restored.flood, before.flood) << line;
      // Before the program's first feed the way down uses SendOptions::resume_feed; after it, the program's feed.
      if (before.feed > 0) {
        EXPECT_DOUBLE_EQ(restored.feed, before.feed) << line;
      }
      ++resumes;
    }
    EXPECT_GE(resumes, 8u);
  }
}

TEST(Rs274Verify, AResumeRestoresInchesOtherPlanesAndWorkOffsets) {
  // A hand-written program in inches, in G59.1, with XZ arcs: from every line after the first move, the resumed
  // program's moves are the original's (rs274 prints program coordinates, so the offset's values do not matter).
  const std::vector<std::string> p = {"G20 G90 G59.1", "T1 M6", "G0 X0 Y0 Z1", "S1000 M3", "G1 Z0 F10",
                                      "G18 G2 X1 Z0 I0.5 K0", "G3 X2 Z0 R0.5", "G1 Y0.5", "G17 G0 Z1", "M5", "M30"};
  const Rs274Result whole = run_rs274(p);
  ASSERT_TRUE(whole.ok) << whole.error;
  for (size_t line = 4; line <= p.size(); ++line) {
    control::SendOptions so;
    so.from_line = line;
    const std::vector<std::string> resumed = control::resumed_program(p, so, "linuxcnc");
    const size_t preamble = resumed.size() - (p.size() - line + 1);
    EXPECT_NE(std::find(resumed.begin(), resumed.end(), "G20 G" + std::to_string(state_before(p, line - 1).plane) +
                                                            " G59.1 G90 G94"),
              resumed.end())
        << line;
    const Rs274Result r = run_rs274(resumed);
    ASSERT_TRUE(r.ok) << "from line " << line << ": " << r.error;
    const std::vector<CanonMove> expected = moves_from(p, whole, line), got = moves_from(resumed, r, preamble + 1);
    ASSERT_EQ(got.size(), expected.size()) << line;
    for (size_t k = 0; k < got.size(); ++k) {
      EXPECT_EQ(got[k].shape, expected[k].shape) << line << ", move " << k;
      EXPECT_EQ(got[k].plane, expected[k].plane) << line << ", move " << k;
      EXPECT_LT((got[k].to - expected[k].to).cwiseAbs().maxCoeff(), 1e-4) << line << ", move " << k;
      EXPECT_LT((got[k].centre - expected[k].centre).cwiseAbs().maxCoeff(), 1e-4) << line << ", move " << k;
    }
  }
}
