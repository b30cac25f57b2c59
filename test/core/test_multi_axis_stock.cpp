// The in-process stock cut by multi-axis moves (stock/multi_axis_sweep.hpp): known volumes, every point against a
// brute-force sweep of the tool at a thousand poses per move (code of this file alone), a cut that leaves material
// above it (what a height field cannot hold), and a five-axis finish of a dome: nothing of the part cut, the
// dome's surface reached to its scallop.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "multi_axis_parts.hpp"
#include "rosmill/error.hpp"
#include "rosmill/plan/five_axis_finish.hpp"
#include "rosmill/stock/in_process_stock.hpp"
#include "rosmill/stock/multi_axis_program.hpp"

using namespace rosmill::core;
using namespace rosmill::core::stock;

namespace {

constexpr double kDeg = M_PI / 180.0;

Tool ball_tool(double diameter, double flutes) {
  Tool t;
  t.id = 5;
  t.cutter = Cutter::ball(diameter);
  t.cutter.flute_length = flutes;
  return t;
}

MultiAxisProgram one_move(const Tool& tool, const Vec3& from, const Vec3& axis_from, const Vec3& to,
                          const Vec3& axis_to, bool rapid = false) {
  MultiAxisProgram p;
  p.tools.push_back(tool);
  AxisMove m;
  m.from = from;
  m.to = to;
  m.axis_from = axis_from;
  m.axis_to = axis_to;
  m.rapid = rapid;
  m.source = 7;
  p.moves.push_back(m);
  return p;
}

// The brute force: the tool's flutes (the segment from the ball's centre to r below their end, grown by the
// radius) at `poses` poses along the move, the tip straight, the axis interpolated and normalised.
double brute_distance(const Vec3& p, const AxisMove& m, double r, double flutes, int poses = 1000) {
  double best = INFINITY;
  for (int k = 0; k <= poses; ++k) {
    const double s = double(k) / poses;
    const Vec3 axis = (m.axis_from + s * (m.axis_to - m.axis_from)).normalized();
    const Vec3 a = m.from + s * (m.to - m.from) + r * axis, b = a + (flutes - 2 * r) * axis;
    const Vec3 d = b - a;
    const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (a + t * d)).norm() - r);
  }
  return best;
}

}  // namespace

TEST(MultiAxisStock, AFixedTiltedAxisSweepsTheSteinerVolumeOfItsParallelogram) {
  // A ball of 6 with 24 mm of flutes, its axis 30 degrees off +Z in XZ, moved 10 mm along y deep inside a block:
  // the flutes sweep the parallelogram of the move and the 18 mm from the ball's centre to 3 mm below the flutes'
  // end, grown by 3 mm,
  // whose volume is 2 A r + (pi / 2) P r^2 + (4 / 3) pi r^3 (Steiner's formula for a plane convex set).
  InProcessStock stock = InProcessStock::box(Box3{Vec3(-30, -30, -30), Vec3(30, 30, 30)}, 0.2);
  const double r = 3, flutes = 24, length = 10, reach = flutes - 2 * r;
  const Vec3 axis(std::sin(30 * kDeg), 0, std::cos(30 * kDeg));
  const RemovalReport rep =
      stock.remove(one_move(ball_tool(6, flutes), Vec3(-5, -5, -20), axis, Vec3(-5, 5, -20), axis));
  const double area = length * reach, perimeter = 2 * (length + reach);
  const double expected = 2 * area * r + 0.5 * M_PI * perimeter * r * r + 4.0 / 3.0 * M_PI * r * r * r;
  EXPECT_NEAR(rep.removed_mm3, expected, 0.005 * expected);
  EXPECT_EQ(rep.rapid_cut_cells, 0u);
  EXPECT_NEAR(rep.feed_mm, length, 1e-9);
  EXPECT_EQ(rep.air_feed_mm, 0.0);
  // The exact queries agree: the ball's centre path and the flutes' end are gone, a point 0.05 mm beyond is not.
  EXPECT_FALSE(stock.material_at(Vec3(-5, 0, -20) + r * axis));
  EXPECT_FALSE(stock.material_at(Vec3(-5, 0, -20) + (flutes - 0.05) * axis));
  EXPECT_TRUE(stock.material_at(Vec3(-5, 0, -20) + (flutes + 0.05) * axis));
  EXPECT_TRUE(stock.material_at(Vec3(-5, 0, -20) + r * axis - Vec3(0, 0, r + 0.05)));
}

TEST(MultiAxisStock, EveryPointOfATurningMoveAgreesWithABruteForceSweep) {
  // Across the block's top 2 mm deep, the axis turning from +Z to 40 degrees about x while the tip goes 20 mm
  // along x: each point is material exactly where no pose of the tool covers it (a margin of 0.01 mm for the
  // steps' sagitta and the brute force's own spacing).
  const Box3 box{Vec3(-20, -15, -15), Vec3(20, 15, 0)};
  InProcessStock stock = InProcessStock::box(box, 0.25);
  const double r = 3, flutes = 18;
  const Vec3 a1(0, -std::sin(40 * kDeg), std::cos(40 * kDeg));
  const MultiAxisProgram program = one_move(ball_tool(6, flutes), Vec3(-10, 0, -2), Vec3::UnitZ(), Vec3(10, 0, -2), a1);
  const RemovalReport rep = stock.remove(program);
  EXPECT_GT(rep.removed_mm3, 0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> ux(-14, 14), uy(-8, 14), uz(-7, 0);
  int inside = 0, outside = 0;
  double removed_by_brute = 0;
  const int samples = 20000, volume_samples = 100000;
  for (int k = 0; k < volume_samples; ++k) {
    const Vec3 p(ux(rng), uy(rng), uz(rng));
    if (k >= samples) {  // the volume alone, at poses 0.1 mm apart
      removed_by_brute += brute_distance(p, program.moves[0], r, flutes, 200) < 0;
      continue;
    }
    const double d = brute_distance(p, program.moves[0], r, flutes);
    removed_by_brute += d < 0;
    if (d < -0.01) {
      ++inside;
      EXPECT_FALSE(stock.material_at(p)) << "the tool passed through " << p.transpose();
    } else if (d > 0.01) {
      ++outside;
      EXPECT_TRUE(stock.material_at(p)) << "no pose of the tool reaches " << p.transpose();
    }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
  // The dexels' volume against the brute force's share of the sampled box (its standard error about 1.5 %).
  const double brute_mm3 = removed_by_brute / volume_samples * (28.0 * 22.0 * 7.0);
  EXPECT_NEAR(rep.removed_mm3, brute_mm3, 0.04 * brute_mm3);
}

TEST(MultiAxisStock, ATiltedCutLeavesMaterialAboveItOnTheSameVerticalLine) {
  // The tool leaning 60 degrees, its ball 5 mm inside a block's side and 8 mm below its top, moved along y: a
  // vertical line over the ball keeps material above the cut and below it (two spans), which a height field
  // seen from above could not hold.
  InProcessStock stock = InProcessStock::box(Box3{Vec3(0, -10, -20), Vec3(20, 10, 0)}, 0.25);
  const Vec3 axis(-std::sin(60 * kDeg), 0, std::cos(60 * kDeg));
  stock.remove(one_move(ball_tool(6, 12), Vec3(5, -5, -8), axis, Vec3(5, 5, -8), axis));
  const Vec3 centre = Vec3(5, 0, -8) + 3 * axis;
  EXPECT_FALSE(stock.material_at(centre));
  EXPECT_TRUE(stock.material_at(Vec3(centre.x(), 0, -1)));   // above: the tool leans away from it
  EXPECT_TRUE(stock.material_at(Vec3(centre.x(), 0, -15)));  // below
  const GridSpec& g = stock.grid();
  const size_t c = g.index(g.first_x(centre.x()), g.first_y(0.0));
  EXPECT_EQ(stock.material().end(c) - stock.material().begin(c), 2);
}

TEST(MultiAxisStock, ARapidThatCutsIsACollisionAndAMoveInAirIsAirCutting) {
  InProcessStock stock = InProcessStock::box(Box3{Vec3(-10, -10, -10), Vec3(10, 10, 0)}, 0.5);
  MultiAxisProgram p = one_move(ball_tool(6, 12), Vec3(-5, 0, 10), Vec3::UnitZ(), Vec3(5, 0, 10), Vec3::UnitZ());
  AxisMove into = p.moves[0];
  into.from = into.to;
  into.to = Vec3(5, 0, -1);
  into.rapid = true;
  into.source = 9;
  p.moves.push_back(into);
  const RemovalReport rep = stock.remove(p);
  EXPECT_EQ(rep.air_feed_mm, 10.0);
  EXPECT_TRUE(rep.collided());
  EXPECT_EQ(rep.first_rapid_source, 9u);
}

TEST(MultiAxisStock, FlatEndMillsAndAxesThatAreNoDirectionAreRefusedNamingTheMove) {
  InProcessStock stock = InProcessStock::box(Box3{Vec3(-10, -10, -10), Vec3(10, 10, 0)}, 0.5);
  Tool flat = ball_tool(6, 12);
  flat.cutter = Cutter::flat(6);
  const auto message = [&](const MultiAxisProgram& p) {
    try {
      stock.remove(p);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(one_move(flat, Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX(), Vec3::UnitZ())).find("move 7"),
            std::string::npos);
  const std::string zero =
      message(one_move(ball_tool(6, 12), Vec3::Zero(), Vec3::Zero(), Vec3::UnitX(), Vec3::UnitZ()));
  EXPECT_NE(zero.find("move 7"), std::string::npos) << zero;
  EXPECT_NE(zero.find("not a direction"), std::string::npos) << zero;
  EXPECT_EQ(stock.volume(), InProcessStock::box(Box3{Vec3(-10, -10, -10), Vec3(10, 10, 0)}, 0.5).volume());
}

TEST(MultiAxisStock, AFiveAxisFinishOfADomeCutsNothingOfItAndReachesItsSurfaceToTheScallop) {
  // A hemisphere of radius 15 on a plate, the stock the dome grown by 0.3 mm (what a roughing leaves) on the plate,
  // finished with a ball of 6 at 1 mm stepover.
  const double R = 15;
  const Mesh dome = test_parts::dome_on_plate(R, 22, 4);
  PlanParams p;
  p.tool = ball_tool(6, 24);
  p.tool.feed = 1000;
  p.stepover = 1.0;
  p.tolerance = 0.002;
  p.tool_axis.cone_deg = 40;
  PlanReport plan;
  const Job job = five_axis_finish(dome, p, {}, &plan);
  ASSERT_EQ(job.size(), 1u);
  ASSERT_TRUE(job[0].multi_axis());
  EXPECT_EQ(plan.unreachable_points, 0u);
  // The stock from above: over every 0.1 mm of the plate, the grown dome's top (a scan's raw stock, on the table
  // at the plate's bottom).
  PointCloud top;
  for (double x = -22; x <= 22; x += 0.1)
    for (double y = -22; y <= 22; y += 0.1)
      top.points.emplace_back(x, y, std::sqrt(std::max(0.0, (R + 0.3) * (R + 0.3) - x * x - y * y)));
  top.recompute_bbox();
  InProcessStock stock = InProcessStock::from_cloud(top, -4, 0.25);
  const RemovalReport rep = stock.remove(multi_axis_program_from_job(job));
  EXPECT_EQ(rep.rapid_cut_cells, 0u);
  EXPECT_GT(rep.removed_mm3, 0);
  // Over the dome's surface up to 60 degrees from its top (a ring of samples every 2 degrees each way): 0.02 mm
  // inside is material (no gouge); 0.3 mm outside is cut (reached), and so is the scallop's height outside for
  // all but a few samples. Passes 1 mm apart in XY are w = 1 / cos(theta) apart on the sphere at theta from its
  // top, where a ball of radius 3 on a sphere of 15 leaves cusps w^2 / 8 (1 / 3 + 1 / 15) high.
  int samples = 0, reached = 0;
  for (int t = 0; t <= 30; ++t)
    for (int f = 0; f < 180; ++f) {
      const double th = 2.0 * t * kDeg, ph = 2.0 * f * kDeg;
      const Vec3 n(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
      ++samples;
      EXPECT_TRUE(stock.material_at((R - 0.02) * n)) << "the finish cut into the dome at " << (R * n).transpose();
      EXPECT_FALSE(stock.material_at((R + 0.3) * n)) << "not reached at " << (R * n).transpose();
      const double w = 1.0 / std::cos(th), scallop = w * w / 8 * (1.0 / 3 + 1.0 / R);
      reached += !stock.material_at((R + scallop + 0.01) * n);
    }
  EXPECT_GE(reached, 0.98 * samples);
}
