// The engagement measurement (verify/engagement.hpp) against answers known from the geometry of the cut: a slot
// is 180 degrees, a straight side cut of radial width ae is acos(1 - ae / R), air is 0, a cut around a round boss
// or inside a round hole follows from the two circles, and the removal rate of a slot is its section times its feed.
#include <gtest/gtest.h>

#include <cmath>

#include <tbb/task_arena.h>

#include "error_of.hpp"
#include "rosmill/error.hpp"
#include "rosmill/stock/material_removal.hpp"
#include "rosmill/toolpath/canon_arc.hpp"
#include "rosmill/verify/engagement.hpp"

using namespace rosmill::core;
using namespace rosmill::core::verify;
using stock::GridSpec;
using stock::HeightField;
using stock::MachineProgram;

namespace {

constexpr double kD = 10, kR = 5, kFeed = 600;
constexpr double kRad = M_PI / 180;

double deg(double rad) { return rad / kRad; }

// A 10 mm flat end mill alone in a program.
MachineProgram program_with_tool() {
  MachineProgram p;
  Tool t;
  t.cutter = Cutter::flat(kD);
  p.tools.push_back(t);
  return p;
}

CanonMove line(const Vec3& from, const Vec3& to, bool rapid = false) {
  CanonMove m;
  m.from = from;
  m.to = to;
  m.rapid = rapid;
  m.feed = rapid ? 0.0f : static_cast<float>(kFeed);
  m.source = 1;
  return m;
}

CanonMove arc(const Vec3& from, const Vec3& to, const Vec2& centre, bool ccw) {
  CanonMove m = line(from, to);
  m.shape = ccw ? MoveShape::ArcCCW : MoveShape::ArcCW;
  m.centre = centre;
  return m;
}

// A block of stock from (0, 0, 0) to (100, 60, 10) at the default cell of the program.
HeightField block(const MachineProgram& p) {
  return HeightField::box(GridSpec::covering(Vec2(0, 0), Vec2(100, 60), engagement_cell(p)), 0, 10);
}

// A straight cut along +x at depth 5 with the cutter's axis at y, from outside the block to outside it again.
double straight_cut(double y) {
  MachineProgram p = program_with_tool();
  p.moves.push_back(line(Vec3(-10, y, 5), Vec3(110, y, 5)));
  HeightField stock = block(p);
  return measure_engagement(p, stock).move_deg[0];
}

// acos(1 - ae / R): a side cut of radial width ae (Altintas' exit angle of an up-milling cut).
double side_cut_deg(double ae) { return deg(std::acos(1 - ae / kR)); }

}  // namespace

TEST(Engagement, StatedToleranceHoldsAtTheDefaultCell) {
  const MachineProgram p = program_with_tool();
  EXPECT_DOUBLE_EQ(engagement_cell(p), 0.1);
  EXPECT_LE(engagement_tolerance_deg(kR, engagement_cell(p)), kEngagementToleranceDeg);
  // R / 40 is the coarsest default cell: the stated tolerance holds there too.
  EXPECT_LE(engagement_tolerance_deg(1.0, 1.0 / 40), kEngagementToleranceDeg);
}

TEST(Engagement, FullWidthSlotIs180) {
  EXPECT_NEAR(straight_cut(30), 180.0, kEngagementToleranceDeg);
}

TEST(Engagement, SideCutsAreAcosOfTheirWidth) {
  // The material is y >= 0 (the block's edge): the axis at y = ae - R leaves ae of the cutter in it.
  for (double share : {0.2, 0.5, 0.8}) {
    const double ae = share * kD;
    SCOPED_TRACE(ae);
    EXPECT_NEAR(straight_cut(ae - kR), side_cut_deg(ae), kEngagementToleranceDeg);
  }
  EXPECT_NEAR(side_cut_deg(0.2 * kD), 53.13, 0.01);
  EXPECT_NEAR(side_cut_deg(0.8 * kD), 126.87, 0.01);
}

TEST(Engagement, AirIsZero) {
  EXPECT_EQ(straight_cut(-kR - 1), 0.0);  // beside the block
  MachineProgram p = program_with_tool();
  p.moves.push_back(line(Vec3(-10, 30, 12), Vec3(110, 30, 12)));  // over it
  HeightField stock = block(p);
  const EngagementReport r = measure_engagement(p, stock);
  EXPECT_EQ(r.max_deg, 0.0);
  EXPECT_NEAR(r.histogram_mm[0], r.radial_mm, 1e-9);
  EXPECT_DOUBLE_EQ(r.radial_mm, 120.0);
  EXPECT_EQ(r.removed_mm3, 0.0);
}

TEST(Engagement, SideCutAlongASlantedSlotWall) {
  // A slot at 30 degrees to the grid, then a pass beside it offset by ae: ae of the cutter in the slot's wall (the
  // wall lies across the cells, so the cell's error counts here). At the block's edges the cut is lighter, never
  // heavier: the move's largest engagement is the steady one.
  const Vec2 u(std::cos(30 * kRad), std::sin(30 * kRad)), n(-u.y(), u.x());
  for (double ae : {0.2 * kD, 0.5 * kD}) {
    SCOPED_TRACE(ae);
    MachineProgram p = program_with_tool();
    const Vec2 a = Vec2(10, 10) - 30 * u, b = Vec2(10, 10) + 110 * u;
    p.moves.push_back(line(Vec3(a.x(), a.y(), 5), Vec3(b.x(), b.y(), 5)));
    const Vec2 c = a + ae * n, d = b + ae * n;
    p.moves.push_back(line(Vec3(b.x(), b.y(), 12), Vec3(c.x(), c.y(), 12), true));
    p.moves.push_back(line(Vec3(c.x(), c.y(), 5), Vec3(d.x(), d.y(), 5)));
    HeightField stock = block(p);
    const EngagementReport r = measure_engagement(p, stock);
    EXPECT_NEAR(r.move_deg[0], 180.0, kEngagementToleranceDeg);
    EXPECT_EQ(r.move_deg[1], 0.0);  // a rapid
    EXPECT_NEAR(r.move_deg[2], side_cut_deg(ae), kEngagementToleranceDeg);
  }
}

TEST(Engagement, ArcsAroundABossAndInsideAHole) {
  // A round boss of radius 20 (the stock stands only there), the cutter going round it counter-clockwise with
  // ae = 2 of it: the leading half meets the boss from where the two circles cross up to the normal towards the
  // boss's centre, beta = acos((rho^2 + R^2 - Rb^2) / (2 rho R)); lighter than the straight cut's 53.13.
  const Vec2 centre(50, 30);
  const double Rb = 20, ae = 2, rho = Rb + kR - ae;
  const double beta = deg(std::acos((rho * rho + kR * kR - Rb * Rb) / (2 * rho * kR)));
  // A round hole of radius 20 in the block, the cutter inside it clockwise with ae = 2 of the wall: the cutter
  // circle's points beyond the hole, gamma = acos((Rh^2 - rho^2 - R^2) / (2 rho R)); heavier than straight.
  const double rho_in = Rb - kR + ae;
  const double gamma = deg(std::acos((Rb * Rb - rho_in * rho_in - kR * kR) / (2 * rho_in * kR)));
  for (bool boss : {true, false}) {
    SCOPED_TRACE(boss ? "boss" : "hole");
    MachineProgram p = program_with_tool();
    const double r = boss ? rho : rho_in;
    const Vec3 start(centre.x() + r, centre.y(), 5);
    p.moves.push_back(arc(start, start, centre, boss));  // a full turn
    HeightField stock = block(p);
    for (int j = 0; j < stock.grid.ny; ++j)
      for (int i = 0; i < stock.grid.nx; ++i) {
        const bool inside = std::hypot(stock.grid.cx(i) - centre.x(), stock.grid.cy(j) - centre.y()) <= Rb;
        if (inside != boss) stock.top[stock.grid.index(i, j)] = 0;
      }
    const EngagementReport e = measure_engagement(p, stock);
    // Every sample of the turn is one of the same cut: its 95th percentile is the cut's engagement.
    EXPECT_NEAR(e.p95_deg, boss ? beta : gamma, kEngagementToleranceDeg);
    EXPECT_NEAR(e.radial_mm, 2 * M_PI * r, 1e-6);
  }
  EXPECT_NEAR(beta, 47.96, 0.01);
  EXPECT_NEAR(gamma, 59.61, 0.01);
}

TEST(Engagement, ArcIsMeasuredAsItCutsItsOwnPath) {
  // A full circle of radius 2 with a 10 mm cutter (circular interpolation of a hole): the turn's end runs in what its
  // start cleared, so a second turn cuts nothing and the first ends lighter than it began.
  MachineProgram p = program_with_tool();
  const Vec3 start(52, 30, 5);
  p.moves.push_back(line(Vec3(52, 30, 12), start));  // a plunge
  p.moves.push_back(arc(start, start, Vec2(50, 30), true));
  p.moves.push_back(arc(start, start, Vec2(50, 30), true));
  HeightField stock = block(p);
  const EngagementReport r = measure_engagement(p, stock);
  EXPECT_EQ(r.plunges, 1u);
  EXPECT_DOUBLE_EQ(r.plunge_mm, 7.0);
  EXPECT_EQ(r.move_deg[0], 0.0);  // a plunge has no radial engagement
  EXPECT_NEAR(r.move_deg[1], 180.0, kEngagementToleranceDeg);
  // The second turn runs along the edge the first cut: at most the cells' rounding of a grazing pass.
  EXPECT_LE(r.move_deg[2], engagement_grazing_deg(kR, r.cell_mm));
  EXPECT_NEAR(engagement_grazing_deg(kR, 0.1), 9.6, 0.05);
  // The removed volume is the circle's swept disc, radius 7, 5 deep (to the cell's area).
  EXPECT_NEAR(r.removed_mm3, M_PI * 49 * 5, 0.01 * M_PI * 49 * 5);
}

TEST(Engagement, SlotRemovalRateIsItsSectionTimesFeed) {
  // A 10 mm slot 5 deep across the 100 mm block: removed D * depth * 100, in the feed time of the 110 mm line
  // (from touching the block to leaving it), so the rate is D * depth * F scaled by 100 / 110.
  MachineProgram p = program_with_tool();
  p.moves.push_back(line(Vec3(-5, 30, 20), Vec3(-5, 30, 5), true));
  p.moves.push_back(line(Vec3(-5, 30, 5), Vec3(105, 30, 5)));
  HeightField stock = block(p);
  const EngagementReport r = measure_engagement(p, stock);
  EXPECT_NEAR(r.removed_mm3, kD * 5 * 100, 0.005 * kD * 5 * 100);
  EXPECT_NEAR(r.feed_minutes, 110 / kFeed, 1e-12);
  EXPECT_NEAR(r.mrr_mm3_per_min, kD * 5 * kFeed * 100 / 110, 0.005 * kD * 5 * kFeed);
  EXPECT_EQ(r.max_deg, 180.0);
  // Entering, the leading half meets the block over 2 acos(-x / R) (x of the axis, -R..0): 170 degrees from x =
  // -R cos(85) on; leaving, all of it but 2 acos((100 - x) / R) around the front: 170 up to x = 100 - R cos(5);
  // past the block's end, air.
  const double heavy = 100 - kR * std::cos(5 * kRad) + kR * std::cos(85 * kRad);
  EXPECT_NEAR(r.histogram_mm[kEngagementBins - 1], heavy, 0.25);
  EXPECT_NEAR(r.histogram_mm[0], 5 + kR * (1 - std::cos(5 * kRad)) + kR * std::cos(85 * kRad), 0.25);
  EXPECT_NEAR(r.p95_deg, 180.0, 1e-9);
}

TEST(Engagement, FeedsAreRetimedAfterTheyChange) {
  MachineProgram p = program_with_tool();
  p.moves.push_back(line(Vec3(-5, 30, 5), Vec3(105, 30, 5)));
  HeightField stock = block(p);
  EngagementReport r = measure_engagement(p, stock);
  p.moves[0].feed = 2 * kFeed;
  retime_engagement(r, p);
  EXPECT_NEAR(r.feed_minutes, 110 / (2 * kFeed), 1e-12);
  EXPECT_NEAR(r.mrr_mm3_per_min, 2 * kD * 5 * kFeed * 100 / 110, 1e-6 * kD * 5 * kFeed);
}

TEST(Engagement, GridCoversTheFeedsOnlyAndCoarsensToItsLimit) {
  MachineProgram p = program_with_tool();
  p.moves.push_back(line(Vec3(40, 30, 5), Vec3(60, 30, 5)));
  Box3 stock;
  stock.add(Vec3(0, 0, 0));
  stock.add(Vec3(100, 60, 10));
  const GridSpec g = engagement_grid(p, stock);
  EXPECT_DOUBLE_EQ(g.cell, 0.1);
  EXPECT_NEAR(g.x0, 40 - kR - 0.1, 1e-9);
  EXPECT_NEAR(g.nx * g.cell, 20 + 2 * (kR + 0.1), 0.2);
  EngagementOptions o;
  o.max_cells = 1000;
  EXPECT_LE(engagement_grid(p, stock, o).cells(), 1000u);
  EXPECT_GT(engagement_grid(p, stock, o).cell, 0.1);
}

TEST(Engagement, BadInputIsRefusedWithTheMove) {
  MachineProgram p = program_with_tool();
  p.moves.push_back(line(Vec3(0, 0, 5), Vec3(10, 0, 5)));
  p.moves[0].feed = 0;
  p.moves[0].source = 7;
  HeightField stock = block(p);
  EXPECT_NE(error_of([&] { measure_engagement(p, stock); }).find("toolpath move 7: a feed move without a positive feed"),
            std::string::npos);
  p.moves[0].feed = kFeed;
  p.moves[0].tool = 3;
  EXPECT_NE(error_of([&] { measure_engagement(p, stock); }).find("names a tool the program does not have"),
            std::string::npos);
  p.moves[0].tool = 0;
  EngagementOptions o;
  o.angle_step_deg = 0;
  EXPECT_NE(error_of([&] { measure_engagement(p, stock, o); }).find("angle_step_deg"), std::string::npos);
}

// The program is measured in chunks side by side, each chunk's measurer first passing the moves before it: every
// move must read as one measurer reading them all reads it, and the stock end the same. A zigzag pocketing of the
// block, six levels 1.5 mm apart with a helix-free plunge and a circle at each, long enough for two chunks.
TEST(Engagement, ChunksSideBySideReadAsOneMeasurerReadsThemAll) {
  MachineProgram p = program_with_tool();
  for (int level = 1; level <= 6; ++level) {
    const double z = 10 - 1.5 * level;
    p.moves.push_back(line(Vec3(-6, -2, 12), Vec3(-6, -2, z), true));
    for (int row = 0; row <= 16; ++row) {
      const double y = -2 + 4 * row, x0 = row % 2 ? 106 : -6, x1 = row % 2 ? -6 : 106;
      p.moves.push_back(line(Vec3(x0, y, z), Vec3(x1, y, z)));
      if (row < 16) p.moves.push_back(line(Vec3(x1, y, z), Vec3(x1, y + 4, z)));
    }
    const Vec3 s(58, 30, z - 0.5);
    p.moves.push_back(line(Vec3(-6, 62, z), Vec3(-6, 62, 12), true));
    p.moves.push_back(line(Vec3(58, 30, 12), s, true));
    p.moves.push_back(arc(s, s, Vec2(50, 30), true));
  }
  const auto measured = [&](int cores, HeightField& stock) {
    tbb::task_arena arena(cores);
    return arena.execute([&] { return measure_engagement(p, stock); });
  };
  HeightField one = block(p), two = block(p);
  const EngagementReport a = measured(1, one), b = measured(2, two);
  ASSERT_EQ(a.move_deg.size(), p.moves.size());
  EXPECT_EQ(a.move_deg, b.move_deg);
  EXPECT_EQ(one.top, two.top);
  EXPECT_EQ(one.cut_by, two.cut_by);
  EXPECT_EQ(a.max_deg, b.max_deg);
  EXPECT_EQ(a.p95_deg, b.p95_deg);
  EXPECT_EQ(a.plunges, b.plunges);
  for (int k = 0; k < kEngagementBins; ++k) EXPECT_NEAR(a.histogram_mm[k], b.histogram_mm[k], 1e-12 * a.radial_mm) << k;  // summed in another order
  EXPECT_NEAR(a.radial_mm, b.radial_mm, 1e-12 * a.radial_mm);
  EXPECT_GT(a.radial_mm, 10000.0);  // two chunks' worth of samples at the 0.2 mm step
  EXPECT_EQ(a.max_deg, 180.0);      // the first row of each level is a slot
}
