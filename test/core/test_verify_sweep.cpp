// The material removal simulation against its slow reference and against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <random>

#include "rosmill/verify/gcode_reader.hpp"
#include "rosmill/verify/material_removal.hpp"

using namespace rosmill;
using namespace rosmill::verify;

namespace {

MachineProgram one_move(const SimMove& m, const Cutter& c) {
  MachineProgram p;
  Tool t;
  t.cutter = c;
  p.tools.push_back(t);
  p.moves.push_back(m);
  return p;
}

// Every cell of the grid agrees with the sampled reference (which can only be higher, by its sampling error).
// Cells within 1e-6 mm of the footprint's rim may go either way; `slack` is the allowed excess over the reference
// (the chords of a helix sit inside the arc by up to the arc tolerance).
void expect_matches_reference(const SimMove& m, const Cutter& c, double slack = 1e-4) {
  Cutter inner = c;
  inner.diameter -= 2e-6;
  const GridSpec g = GridSpec::covering(Vec2(-12, -12), Vec2(12, 12), 0.5);
  Stock s = Stock::box(g, -50, 50);
  simulate(one_move(m, c), s);
  int cut = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double ref = lowest_bottom_reference(m, c, g.cx(i), g.cy(j), 2000);
      const double got = s.top[g.index(i, j)];
      if (std::isinf(ref) || ref > 50) {
        if (got < 50.0f && std::isinf(lowest_bottom_reference(m, inner, g.cx(i), g.cy(j), 2000))) continue;
        ASSERT_FLOAT_EQ(got, 50.0f) << i << "," << j;
        continue;
      }
      if (got == 50.0f && std::isinf(lowest_bottom_reference(m, inner, g.cx(i), g.cy(j), 2000))) continue;
      ++cut;
      ASSERT_LE(got, ref + slack) << std::setprecision(9) << cutter_type_name(c.type) << " cell " << i << "," << j;
      ASSERT_GE(got, ref - 0.02) << cutter_type_name(c.type) << " cell " << i << "," << j;
    }
  EXPECT_GT(cut, 20);
}

SimMove line(Vec3 a, Vec3 b) {
  SimMove m;
  m.from = a;
  m.to = b;
  return m;
}

SimMove arc(Vec3 a, Vec3 b, Vec2 c, bool ccw) {
  SimMove m = line(a, b);
  m.shape = ccw ? MoveShape::ArcCCW : MoveShape::ArcCW;
  m.centre = c;
  return m;
}

const Cutter kCutters[] = {Cutter::flat(6), Cutter::ball(6), Cutter::bull(8, 1.5)};

}  // namespace

TEST(VerifySweep, LevelLineMatchesReference) {
  for (const Cutter& c : kCutters) expect_matches_reference(line({-5, -3, 1}, {6, 4, 1}), c);
}

TEST(VerifySweep, RampLineMatchesReference) {
  for (const Cutter& c : kCutters) {
    expect_matches_reference(line({-5, -3, 4}, {6, 4, -2}), c);
    expect_matches_reference(line({-1, 2, -3}, {3, -2, 5}), c);
    expect_matches_reference(line({0.3, 0.2, 5}, {0.3, 0.2, -4}), c);  // a plunge
    expect_matches_reference(line({-4, 0, 5}, {-3.8, 0.1, -4}), c);   // nearly a plunge
  }
}

TEST(VerifySweep, ArcsMatchReference) {
  for (const Cutter& c : kCutters) {
    expect_matches_reference(arc({5, 0, 1}, {0, 5, 1}, {0, 0}, true), c);     // quarter CCW
    expect_matches_reference(arc({5, 0, 1}, {0, 5, 1}, {0, 0}, false), c);    // three quarters CW
    expect_matches_reference(arc({4, 0, 1}, {4, 0, 1}, {0, 0}, true), c);     // full circle
    expect_matches_reference(arc({5, 0, 3}, {-5, 0, -1}, {0, 0}, true), c, 0.02);  // helical half turn
  }
}

TEST(VerifySweep, BallSlotDepthAndWidthAreExact) {
  // A 6 mm ball along x at z = 2 in a stock whose top is at 5: the slot's cross-section is the ball's circle.
  const GridSpec g = GridSpec::covering(Vec2(0, -10), Vec2(40, 10), 0.1);
  Stock s = Stock::box(g, 0, 5);
  simulate(one_move(line({5, 0.05, 2}, {35, 0.05, 2}), Cutter::ball(6)), s);
  for (int j = 0; j < g.ny; ++j) {
    const double y = g.cy(j) - 0.05, expect = std::abs(y) < 3 ? std::min(5.0, 2 + 3 - std::sqrt(9 - y * y)) : 5.0;
    EXPECT_NEAR(s.top[g.index(200, j)], expect, 1e-5) << "y " << y;
  }
}

TEST(VerifySweep, ParallelBandsEqualSerial) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10, 10), z(-2, 2);
  MachineProgram p;
  for (const Cutter& c : kCutters) {
    Tool t;
    t.cutter = c;
    p.tools.push_back(t);
  }
  Vec3 at(0, 0, 3);
  for (int k = 0; k < 300; ++k) {
    SimMove m = line(at, Vec3(u(rng), u(rng), z(rng)));
    m.tool = static_cast<uint16_t>(k / 100);
    m.source = k + 1;
    at = m.to;
    p.moves.push_back(m);
  }
  const GridSpec g = GridSpec::covering(Vec2(-15, -15), Vec2(15, 15), 0.25);
  Stock a = Stock::box(g, -10, 5), b = Stock::box(g, -10, 5);
  SimulationOptions serial;
  serial.parallel = false;
  serial.band_rows = 1000;
  simulate(p, a, serial);
  simulate(p, b);
  EXPECT_EQ(a.top, b.top);
  EXPECT_EQ(a.cut_by, b.cut_by);
}
