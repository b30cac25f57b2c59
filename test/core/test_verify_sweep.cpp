// The material removal simulation against its slow reference and against closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <random>

#include "rosmill/verify/gcode_reader.hpp"
#include "rosmill/stock/material_removal.hpp"

using namespace rosmill::core;
using namespace rosmill::core::verify;
using namespace rosmill::core::stock;

namespace {

MachineProgram one_move(const CanonMove& m, const Cutter& c) {
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
void expect_matches_reference(const CanonMove& m, const Cutter& c, double slack = 1e-4) {
  Cutter inner = c;
  inner.diameter -= 2e-6;
  const GridSpec g = GridSpec::covering(Vec2(-12, -12), Vec2(12, 12), 0.5);
  HeightField s = HeightField::box(g, -50, 50);
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

CanonMove line(Vec3 a, Vec3 b) {
  CanonMove m;
  m.from = a;
  m.to = b;
  return m;
}

CanonMove arc(Vec3 a, Vec3 b, Vec2 c, bool ccw) {
  CanonMove m = line(a, b);
  m.shape = ccw ? MoveShape::ArcCCW : MoveShape::ArcCW;
  m.centre = c;
  return m;
}

const Cutter kCutters[] = {Cutter::flat(6), Cutter::ball(6), Cutter::bull(8, 1.5)};

// A program that exercises every kind of piece and joint: random walks of short lines (level, rising, falling),
// vertical plunges and retracts, level and helical arcs, rapids and tool changes, plus a dense zig-zag raster
// over a bump (a smooth chain with turns), for each cutter.
MachineProgram mixed_program(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  MachineProgram p;
  for (const Cutter& c : kCutters) {
    Tool t;
    t.cutter = c;
    p.tools.push_back(t);
  }
  Vec3 at(0, 0, 3);
  uint32_t source = 0;
  auto push = [&](CanonMove m) {
    m.from = at;
    m.source = ++source;
    at = m.to;
    p.moves.push_back(m);
  };
  for (uint16_t tool = 0; tool < 3; ++tool) {
    for (int k = 0; k < 300; ++k) {
      CanonMove m;
      m.tool = tool;
      const double r = u(rng);
      if (r < 0.05) {  // a rapid somewhere
        m.rapid = true;
        m.to = Vec3(-12 + 24 * u(rng), -12 + 24 * u(rng), -1 + 4 * u(rng));
      } else if (r < 0.15) {  // vertical
        m.to = Vec3(at.x(), at.y(), -3 + 5 * u(rng));
      } else if (r < 0.2) {  // an arc, level or helical, about a centre 0.5..4 mm away
        const double rho = 0.5 + 3.5 * u(rng), a0 = 2 * M_PI * u(rng), sweep = (u(rng) - 0.5) * 4 * M_PI;
        m.centre = at.head<2>() - rho * Vec2(std::cos(a0), std::sin(a0));
        m.shape = sweep > 0 ? MoveShape::ArcCCW : MoveShape::ArcCW;
        const double a1 = a0 + sweep;
        m.to = Vec3(m.centre.x() + rho * std::cos(a1), m.centre.y() + rho * std::sin(a1),
                    u(rng) < 0.5 ? at.z() : at.z() + u(rng) - 0.5);
      } else {  // a short line: level, rising or falling
        const double len = 0.05 + 2 * u(rng) * u(rng), dir = 2 * M_PI * u(rng), q = u(rng);
        const double dz = q < 0.3 ? 0.0 : (q - 0.65) * len;
        m.to = at + Vec3(len * std::cos(dir), len * std::sin(dir), dz);
      }
      m.to.x() = std::clamp(m.to.x(), -12.0, 12.0);
      m.to.y() = std::clamp(m.to.y(), -12.0, 12.0);
      if (m.shape != MoveShape::Line &&
          std::abs((m.to.head<2>() - m.centre).norm() - (at.head<2>() - m.centre).norm()) > 1e-9)
        m.shape = MoveShape::Line;  // clamped off its circle (inside or outside): no longer an arc
      push(m);
    }
    // A dense raster over a bump (descending and ascending, lines joined by U-turns).
    for (int line = 0; line < 12; ++line) {
      for (int q = 0; q <= 120; ++q) {
        const double x = line % 2 ? 9 - 0.15 * q : -9 + 0.15 * q, y = -9 + 1.5 * line;
        CanonMove m;
        m.tool = tool;
        m.to = Vec3(x, y, 2 * std::exp(-(x * x + y * y) / 30) - 1);
        push(m);
      }
    }
  }
  return p;
}

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
  HeightField s = HeightField::box(g, 0, 5);
  simulate(one_move(line({5, 0.05, 2}, {35, 0.05, 2}), Cutter::ball(6)), s);
  for (int j = 0; j < g.ny; ++j) {
    const double y = g.cy(j) - 0.05, expect = std::abs(y) < 3 ? std::min(5.0, 2 + 3 - std::sqrt(9 - y * y)) : 5.0;
    EXPECT_NEAR(s.top[g.index(200, j)], expect, 1e-5) << "y " << y;
  }
}

TEST(VerifySweep, ParallelBandsEqualSerial) {
  const MachineProgram p = mixed_program(7);
  const GridSpec g = GridSpec::covering(Vec2(-16, -16), Vec2(16, 16), 0.25);
  HeightField a = HeightField::box(g, -10, 2), b = HeightField::box(g, -10, 2);
  SimulationOptions serial;
  serial.parallel = false;
  serial.band_rows = 1000;
  simulate(p, a, serial);
  simulate(p, b);
  EXPECT_EQ(a.top, b.top);
  EXPECT_EQ(a.cut_by, b.cut_by);
  EXPECT_NE(a.top, HeightField::box(g, -10, 2).top);
}


TEST(VerifySweep, PrunedChainsEqualWholeSweeps) {
  // The pruned sweep visits far fewer cells than sweeping each move whole; the stock and the finishing trace it
  // leaves are the same (to a float's rounding: each cell's lowest value comes from the same move).
  const GridSpec g = GridSpec::covering(Vec2(-16, -16), Vec2(16, 16), 0.25);
  for (unsigned seed : {1u, 2u, 3u, 6u}) {  // 3 and 6 clamp arcs onto a smaller radius
    const MachineProgram p = mixed_program(seed);
    HeightField pruned = HeightField::box(g, -10, 2), whole = HeightField::box(g, -10, 2);
    SimulationOptions o;
    o.trace_radius = 1.0;
    const SimulationResult a = simulate(p, pruned, o);
    o.prune = false;
    const SimulationResult b = simulate(p, whole, o);
    EXPECT_LT(a.cells_visited, b.cells_visited);
    EXPECT_EQ(a.rapid_cut_cells, b.rapid_cut_cells);
    EXPECT_EQ(a.first_rapid_cut, b.first_rapid_cut);
    size_t cut = 0, same_move = 0;
    for (size_t c = 0; c < g.cells(); ++c) {
      ASSERT_NEAR(pruned.top[c], whole.top[c], 2e-6) << "seed " << seed << " cell " << c;
      cut += whole.top[c] < 2.0f;
      same_move += pruned.cut_by[c] == whole.cut_by[c];
      const float ta = a.finish_axis_d2[c], tb = b.finish_axis_d2[c];
      if (std::isinf(tb)) ASSERT_TRUE(std::isinf(ta)) << "seed " << seed << " cell " << c;
      else ASSERT_NEAR(ta, tb, 1e-5) << "seed " << seed << " cell " << c;
    }
    EXPECT_GT(cut, g.cells() / 2);
    EXPECT_GT(same_move, g.cells() * 99 / 100);  // ties (equal heights from two moves) may name either
  }
}
