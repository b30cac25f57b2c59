// The in-process stock cut by multi-axis moves (stock/multi_axis_sweep.hpp): known volumes, every point against a
// brute-force sweep of the tool at a thousand poses per move (code of this file alone), a cut that leaves material
// above it (what a height field cannot hold), and a five-axis finish of a dome: nothing of the part cut, the
// dome's surface reached to its scallop. Then the verifier of multi-axis programs over the whole surface
// (verify/multi_axis.hpp), in the core and as `rosmill verify` runs on a five-axis toolpath file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <random>

#include "cli_run.hpp"
#include "multi_axis_parts.hpp"
#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/five_axis_finish.hpp"
#include "rosmill/stock/in_process_stock.hpp"
#include "rosmill/stock/multi_axis_program.hpp"
#include "rosmill/verify/multi_axis.hpp"

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

// A five-axis finish of a dome with a ball of 6 (24 mm of flutes) at 1 mm stepover, within a cone of 40 degrees.
PlanParams dome_finish() {
  PlanParams p;
  p.tool = ball_tool(6, 24);
  p.tool.feed = 1000;
  p.stepover = 1.0;
  p.tolerance = 0.002;
  p.tool_axis.cone_deg = 40;
  return p;
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
  const PlanParams p = dome_finish();
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

TEST(MultiAxisVerify, ADomeFinishIsClearAndLeavesItsScallopAndTheSameToolpathLoweredGougesByThatMuch) {
  // The dome's five-axis finish verified from the stock the dome grown by 0.3 mm (a closed mesh): no gouge; on the
  // dome down to 60 degrees from its top nothing above the cusp of its passes; the most left, and all that no tool
  // came near, at its foot (the concave corner with the plate that a ball of 3 mm cannot enter). Then the toolpath
  // 0.05 mm lower: a gouge that deep, named by a move.
  const double R = 15;
  const Mesh dome = test_parts::dome_on_plate(R, 22, 4, 96, 32);
  const Mesh grown = test_parts::dome_on_plate(R + 0.3, 22, 4, 96, 32);
  ASSERT_TRUE(grown.closed());
  const PlanParams p = dome_finish();
  const Job job = five_axis_finish(dome, p, {});
  ASSERT_EQ(job[0].tool.stepover, 1.0);
  verify::StockSpec stock;
  stock.kind = verify::StockSpec::Kind::Mesh;
  stock.mesh = &grown;
  verify::VerifyOptions o;
  o.resolution = 0.25;
  const verify::MultiAxisVerifyResult r =
      verify::verify_multi_axis(dome, multi_axis_program_from_job(job), stock, o, 1.0);
  EXPECT_EQ(r.max_gouge_mm, 0.0) << "at " << r.gouge_at.transpose() << ", move " << r.gouge_source;
  EXPECT_FALSE(r.removal.collided());
  EXPECT_GT(r.samples, 10000u);
  EXPECT_NEAR(r.limit_mm, 0.01 + (3 - std::sqrt(9 - 0.25)), 1e-9);
  const auto at_foot = [&](const Vec3& q) { return q.z() < 3.5 && q.head<2>().norm() < R + 1.5; };
  EXPECT_TRUE(at_foot(r.max_rest_at)) << r.max_rest_at.transpose();
  double dome_area = 0, foot_band = 0;
  int on_dome = 0;
  for (size_t k = 0; k < r.samples; ++k) {
    const Vec3& q = r.surface.points[k];
    if (at_foot(q) && q.z() >= -1e-9) foot_band += r.surface.weights[k];
    const double th = std::acos(std::clamp(q.z() / q.norm(), -1.0, 1.0));
    if (q.z() < 1 || std::abs(q.norm() - R) > 0.05 || th > 60 * kDeg) continue;
    ++on_dome;
    dome_area += r.surface.weights[k];
    // Passes 1 mm apart in XY are 1 / cos(theta) apart on the sphere: cusps w^2 / 8 (1 / 3 + 1 / 15) high, over
    // the facets that lie inside the sphere by up to R (1 - cos(pi / 96)) = 0.008 mm.
    const double w = 1.0 / std::cos(th), cusp = w * w / 8 * (1.0 / 3 + 1.0 / R);
    EXPECT_LE(r.rest[k], cusp + 0.008 + 0.01) << "at " << q.transpose();
  }
  EXPECT_GT(on_dome, 5000);
  EXPECT_NEAR(dome_area, 2 * M_PI * R * R * 0.5, 0.02 * 2 * M_PI * R * R);  // the cap to 60 degrees: 2 pi R^2 (1 - cos)
  EXPECT_LT(r.unreached_area_mm2, foot_band);
  EXPECT_LT(r.above_area_mm2, foot_band + 0.02 * dome_area);
  Job lower = job;
  for (ToolpathPass& pass : lower[0].passes)
    for (Move& m : pass.moves) m.to.z() -= 0.05;
  const verify::MultiAxisVerifyResult g = verify::verify_multi_axis(dome, multi_axis_program_from_job(lower), stock, o);
  EXPECT_NEAR(g.max_gouge_mm, 0.05, 0.01) << g.gouge_at.transpose() << " move " << g.gouge_source;
  EXPECT_GT(g.gouge_source, 0u);
  EXPECT_GT(g.gouged_area_mm2, 100.0);
}

TEST(MultiAxisVerify, RosmillVerifyFollowsAFiveAxisToolpathFileWithItsAxes) {
  // As a user runs it: `rosmill plan dome.stl --strategy five-axis -o finish.json`, then `rosmill verify dome.stl
  // finish.json --stock grown.stl`. Before, verify swept the file's cutter locations with a vertical tool.
  const std::string dir = ::testing::TempDir() + "/rosmill_verify5_" + std::to_string(::getpid());
  ASSERT_EQ(std::system(("mkdir -p '" + dir + "'").c_str()), 0);
  write_stl(dir + "/dome.stl", test_parts::dome_on_plate(15, 22, 4, 96, 32));
  write_stl(dir + "/grown.stl", test_parts::dome_on_plate(15.3, 22, 4, 96, 32));
  const CliRun plan = run_rosmill_in(
      dir, "plan dome.stl --strategy five-axis --tool ball:6@5 --stepover 1 --machine " ROSMILL_SOURCE_DIR
           "/config/machine_xyzac_tcp.yaml -o finish.json 2>&1");
  ASSERT_EQ(plan.status, 0) << plan.out;
  const CliRun v = run_rosmill_in(dir, "verify dome.stl finish.json --stock grown.stl --resolution 0.25 --json 2>&1");
  ASSERT_EQ(v.status, 0) << v.out;
  const nlohmann::json j = nlohmann::json::parse(v.out);
  EXPECT_TRUE(j.at("multi_axis").get<bool>());
  EXPECT_EQ(j.at("max_gouge_mm").get<double>(), 0.0) << v.out;
  EXPECT_TRUE(j.at("rapid_into_material_move").is_null()) << v.out;
  EXPECT_GT(j.at("mean_rest_mm").get<double>(), 0.0);
  EXPECT_LT(j.at("mean_rest_mm").get<double>(), 0.05);
  EXPECT_NEAR(j.at("limit_mm").get<double>(), 0.01 + (3 - std::sqrt(9 - 0.25)), 1e-9);  // the file's stepover
  const CliRun text = run_rosmill_in(dir, "verify dome.stl finish.json --stock grown.stl --resolution 0.5 2>&1");
  EXPECT_EQ(text.status, 0) << text.out;
  EXPECT_NE(text.out.find("multi-axis"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("gouge      none"), std::string::npos) << text.out;
  const CliRun machine = run_rosmill_in(dir, "verify dome.stl finish.json --machine " ROSMILL_SOURCE_DIR
                                             "/config/machine_xyzac.yaml --on-table 0,0,0 2>&1");
  EXPECT_EQ(machine.status, 1);
  EXPECT_NE(machine.out.find("without --machine"), std::string::npos) << machine.out;

  // The same finish as G-code for the trunnion's tool-centre-point control (M428: X Y Z the tip, A C the axis):
  // read back with the machine's kinematics, the same figures; with every Z under M428 0.05 mm lower, a gouge
  // of 0.05 mm named by its line.
  const std::string tcp = " --machine " ROSMILL_SOURCE_DIR "/config/machine_xyzac_tcp.yaml";
  const CliRun post = run_rosmill_in(
      dir, "plan dome.stl --strategy five-axis --tool ball:6@5 --stepover 1" + tcp + " -o finish.ngc 2>&1");
  ASSERT_EQ(post.status, 0) << post.out;
  const std::string verify_ngc =
      "verify dome.stl finish.ngc --stock grown.stl --resolution 0.25 --tool 5=ball:6 --stepover 1 --json" + tcp;
  const CliRun g = run_rosmill_in(dir, verify_ngc + " 2>&1");
  ASSERT_EQ(g.status, 0) << g.out;
  const nlohmann::json k = nlohmann::json::parse(g.out);
  EXPECT_EQ(k.at("max_gouge_mm").get<double>(), 0.0) << g.out;
  EXPECT_NEAR(k.at("mean_rest_mm").get<double>(), j.at("mean_rest_mm").get<double>(), 1e-3);
  EXPECT_NEAR(k.at("max_rest_mm").get<double>(), j.at("max_rest_mm").get<double>(), 1e-2);
  std::ifstream in(dir + "/finish.ngc");
  std::ofstream out(dir + "/lower.ngc");
  bool under = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("M428", 0) == 0) under = true;
    if (line.rfind("M429", 0) == 0) under = false;
    const size_t z = line.rfind('Z', 0) == 0                ? 0
                     : line.find(" Z") == std::string::npos ? line.npos
                                                            : line.find(" Z") + 1;
    if (under && z != std::string::npos && line.find('(') == std::string::npos) {
      const size_t end = line.find(' ', z);
      const double v = std::stod(line.substr(z + 1, end - z - 1)) - 0.05;
      line = line.substr(0, z) + "Z" + std::to_string(v) + (end == std::string::npos ? "" : line.substr(end));
    }
    out << line << "\n";
  }
  out.close();
  const CliRun low = run_rosmill_in(
      dir, "verify dome.stl lower.ngc --stock grown.stl --resolution 0.25 --tool 5=ball:6 --json" + tcp + " 2>&1");
  ASSERT_EQ(low.status, 0) << low.out;
  const nlohmann::json l = nlohmann::json::parse(low.out);
  EXPECT_NEAR(l.at("max_gouge_mm").get<double>(), 0.05, 0.01) << low.out;
  EXPECT_GT(l.at("gouge_move").get<int>(), 11) << "a line after M428";
  std::system(("rm -rf '" + dir + "'").c_str());
}
