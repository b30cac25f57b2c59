// Adaptive clearing (plan/adaptive.hpp) and the roughing levels at flat faces (plan/levels.hpp). Every bound is
// checked by code the planner does not share: the engagement by the verifier's measurement on a height field
// (verify/engagement.hpp), the material left and gouges by the stock simulation and the job's reports.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "job_test_options.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/job/job_spec.hpp"
#include "rosmill/plan/adaptive.hpp"
#include "rosmill/plan/levels.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/stock/program.hpp"
#include "rosmill/verify/engagement.hpp"
#include "rosmill/verify/verify.hpp"

using namespace rosmill::core;

namespace {

// The engagement bound adaptive.hpp states (kAdaptiveEngagementSlackDeg over the limit, the corners of the rings
// that turn into an inner corner) plus the verifier's own stated tolerance.
constexpr double kEngagementSlackDeg = kAdaptiveEngagementSlackDeg + verify::kEngagementToleranceDeg;

// A block [0, L] x [0, W] x [0, H] with a rectangular pocket [x0, x1] x [y0, y1] down to H - depth, closed and
// oriented outwards.
Mesh pocket_block(double L, double W, double H, double x0, double x1, double y0, double y1, double depth) {
  std::vector<Vec3> c;
  auto quad = [&](const Vec3& a, const Vec3& b, const Vec3& d, const Vec3& e) {  // counter-clockwise seen outside
    c.insert(c.end(), {a, b, d, a, d, e});
  };
  const double f = H - depth;
  // Outer walls and bottom.
  quad({0, 0, 0}, {L, 0, 0}, {L, 0, H}, {0, 0, H});
  quad({L, 0, 0}, {L, W, 0}, {L, W, H}, {L, 0, H});
  quad({L, W, 0}, {0, W, 0}, {0, W, H}, {L, W, H});
  quad({0, W, 0}, {0, 0, 0}, {0, 0, H}, {0, W, H});
  quad({0, 0, 0}, {0, W, 0}, {L, W, 0}, {L, 0, 0});
  // Top around the pocket: four strips.
  quad({0, 0, H}, {L, 0, H}, {L, y0, H}, {0, y0, H});
  quad({0, y1, H}, {L, y1, H}, {L, W, H}, {0, W, H});
  quad({0, y0, H}, {x0, y0, H}, {x0, y1, H}, {0, y1, H});
  quad({x1, y0, H}, {L, y0, H}, {L, y1, H}, {x1, y1, H});
  // The pocket's walls (facing into it) and floor.
  quad({x0, y0, f}, {x0, y1, f}, {x0, y1, H}, {x0, y0, H});
  quad({x1, y1, f}, {x1, y0, f}, {x1, y0, H}, {x1, y1, H});
  quad({x1, y0, f}, {x0, y0, f}, {x0, y0, H}, {x1, y0, H});
  quad({x0, y1, f}, {x1, y1, f}, {x1, y1, H}, {x0, y1, H});
  quad({x0, y0, f}, {x1, y0, f}, {x1, y1, f}, {x0, y1, f});
  return build_mesh(c);
}

// A block [0, S]^2 x [0, H] with a square ring groove `depth` deep between the squares of half-sizes `outer` and
// `inner` about its centre: a closed channel round an island.
Mesh ring_groove_block(double S, double H, double outer, double inner, double depth) {
  Mesh block = pocket_block(S, S, H, S / 2 - outer, S / 2 + outer, S / 2 - outer, S / 2 + outer, depth);
  // pocket_block's floor is the last two triangles: the groove's floor round the island, the island's walls and
  // its top take its place.
  std::vector<Vec3> c;
  for (size_t t = 0; t + 2 < block.faces.size(); ++t)
    for (int k = 0; k < 3; ++k) c.push_back(block.corner(t, k));
  auto quad = [&](const Vec3& a, const Vec3& b, const Vec3& d, const Vec3& e) {
    c.insert(c.end(), {a, b, d, a, d, e});
  };
  const double f = H - depth, a0 = S / 2 - outer, a1 = S / 2 + outer, b0 = S / 2 - inner, b1 = S / 2 + inner;
  quad({a0, a0, f}, {a1, a0, f}, {a1, b0, f}, {a0, b0, f});  // floor: four strips
  quad({a0, b1, f}, {a1, b1, f}, {a1, a1, f}, {a0, a1, f});
  quad({a0, b0, f}, {b0, b0, f}, {b0, b1, f}, {a0, b1, f});
  quad({b1, b0, f}, {a1, b0, f}, {a1, b1, f}, {b1, b1, f});
  quad({b0, b1, f}, {b0, b0, f}, {b0, b0, H}, {b0, b1, H});  // the island's walls, facing out
  quad({b1, b0, f}, {b1, b1, f}, {b1, b1, H}, {b1, b0, H});
  quad({b0, b0, f}, {b1, b0, f}, {b1, b0, H}, {b0, b0, H});
  quad({b1, b1, f}, {b0, b1, f}, {b0, b1, H}, {b1, b1, H});
  quad({b0, b0, H}, {b1, b0, H}, {b1, b1, H}, {b0, b1, H});  // its top
  return build_mesh(c);
}

PlanParams flat(double diameter, double stepover, double stepdown, double allowance) {
  PlanParams p;
  p.tool = default_tool(Cutter{CutterType::FlatEnd, diameter, 0});
  p.tool.id = 1;  // its number in the controller's table: a program loads it by that
  p.stepover = stepover;
  p.stepdown = stepdown;
  p.allowance = allowance;
  p.tolerance = 0.01;
  return p;
}

struct Planned {
  Job job;
  PlanReport report;
};

Planned adaptive(const Mesh& mesh, const PlanParams& params) {
  const MeshSurface surface(mesh);
  Planned p;
  p.job = adaptive_on(surface, params, AdaptiveOptions{}, {}, &p.report);
  return p;
}

// The verifier's engagement over the program on the plan's box stock: the largest over the feed moves (the entries
// -- a helix or a ramp down, and its turn or pass at the bottom -- are plunges: they cut with the cutter's end).
double measured_level_engagement(const Job& job, const Box3& stock) {
  const stock::MachineProgram program = stock::program_from_job(job);
  std::vector<MoveType> types;
  for (const Toolpath& tp : job)
    for (const ToolpathPass& pass : tp.passes)
      for (const Move& m : pass.moves) types.push_back(m.type);
  EXPECT_EQ(types.size(), program.moves.size());
  stock::HeightField field = stock::HeightField::box(
      verify::engagement_grid(program, stock), stock.min.z(), stock.max.z());
  const verify::EngagementReport r = verify::measure_engagement(program, field);
  double worst = 0;
  for (size_t k = 0; k < program.moves.size() && k < types.size(); ++k)
    if (types[k] == MoveType::Feed) {
      worst = std::max(worst, double(r.move_deg[k]));
    }
  return worst;
}

// Vertices between two feed moves along a level where the path turns sharper than `radius`: the radius of the
// circle through the vertex and its two neighbours (a polyline that samples a curve of radius r gives r).
size_t sharp_turns(const Job& job, double radius) {
  size_t sharp = 0;
  for (const Toolpath& tp : job)
    for (const ToolpathPass& pass : tp.passes) {
      Vec3 from = Vec3::Constant(NAN);
      Vec2 u = Vec2::Zero();  // the last move along the level (zero after any other move)
      for (const Move& m : pass.moves) {
        const bool level = m.type == MoveType::Feed && std::abs(m.to.z() - from.z()) < 1e-9;
        const Vec2 v = level ? Vec2((m.to - from).head<2>()) : Vec2::Zero();
        if (u.norm() > 1e-9 && v.norm() > 1e-9) {
          const double sin_turn = std::abs(u.x() * v.y() - u.y() * v.x()) / (u.norm() * v.norm());
          const bool back = u.dot(v) < 0;
          if (back || (u + v).norm() < 0.9 * radius * 2 * sin_turn) ++sharp;
        }
        if (!level || v.norm() > 1e-9) u = v;
        from = m.to;
      }
    }
  return sharp;
}

verify::VerifyResult verified(const Mesh& design, const Job& job, const Box3& stock, double resolution = 0.25) {
  verify::StockSpec spec;
  spec.kind = verify::StockSpec::Kind::Box;
  spec.box = stock;
  verify::VerifyOptions o;
  o.resolution = resolution;
  return verify::verify_program(design, stock::program_from_job(job), spec, o);
}

// Within `inset` of nothing but the pocket's floor: the largest material left there over the design.
double left_on_floor(const verify::VerifyResult& v, double x0, double x1, double y0, double y1, double inset) {
  const stock::GridSpec& g = v.grid.grid;
  double worst = -INFINITY;
  for (int j = g.first_y(y0 + inset); j <= g.last_y(y1 - inset); ++j)
    for (int i = g.first_x(x0 + inset); i <= g.last_x(x1 - inset); ++i)
      worst = std::max(worst, double(v.grid.deviation[g.index(i, j)]));
  return worst;
}

}  // namespace

TEST(RoughingLevels, FlatFacesGetALevelAtTheirHeightPlusTheAllowance) {
  // The cube's top at 60 with 0.5 mm allowance: CL heights 60.5 over it, 0.5 (the floor) around it.
  std::vector<double> heights(50, 60.5);
  heights.insert(heights.end(), 100, 0.5);
  heights.push_back(33.3);  // a single sample is no face
  EXPECT_EQ(flat_heights(heights, 4, 0.5), std::vector<double>({60.5}));
  const std::vector<double> levels = roughing_levels(65, 0.5, 3, {60.5});
  EXPECT_EQ(levels.front(), 62);
  EXPECT_NE(std::find(levels.begin(), levels.end(), 60.5), levels.end());
  EXPECT_EQ(levels.back(), 0.5);
  EXPECT_TRUE(std::is_sorted(levels.rbegin(), levels.rend()));
  // A step within 0.05 mm above a flat level is cut by it.
  const std::vector<double> merged = roughing_levels(63.52, 0.5, 3, {60.5});
  EXPECT_EQ(std::count_if(merged.begin(), merged.end(), [](double z) { return z > 60.4 && z < 60.6; }), 1);
}

// Roughing the cube (step-down 3, allowance 0.5) left 2 mm on its top before the levels at flat faces: zigzag and
// adaptive now leave the allowance on the top and the sides, as the job's stock model finds it. (Adaptive's level
// on the top once left a pin there, 0.5 x 1 mm and 2 mm high, between the spiral's last turns: the pins a level's
// passes leave are now taken at its end.)
TEST(Adaptive, CubeRoughingLeavesTheAllowanceAdaptiveAndZigzag) {
  for (const char* strategy : {"rough", "adaptive"}) {
    const job::JobSpec spec = job::parse_job(
        std::string("part: primitive:cube\nresolution: 0.5\noperations:\n  - {strategy: ") + strategy +
            ", tool: flat:10@1, stepover: 4, stepdown: 3, allowance: 0.5}\n",
        "cube.yaml", ROSMILL_SOURCE_DIR);
    const job::JobReport r = job::run_job(spec, job_test::options());
    const job::OperationReport& op = r.operations.at(0);
    SCOPED_TRACE(strategy);
    EXPECT_NEAR(op.min_left_mm, 0.5, 0.5 * 0.5 + 1e-6);  // within the stock's cell
    EXPECT_NEAR(op.max_left_mm, 0.5, 0.5 + 1e-6);
    EXPECT_LE(op.gouge_mm, 0.0);
    if (std::string(strategy) == "adaptive") {
      ASSERT_TRUE(op.engagement_measured);
      EXPECT_LE(op.engagement.max_deg, 180.0);
    }
  }
}

// A pass that meets the material from air, with nothing to steer by, turns into it as fast as its turn radius lets
// it; at a concave front it was turned in faster than it could turn back and ended a few steps in, its start given
// up: many short passes linked by loops through air. Each step now keeps a way out. The cast cone (a casting, the
// cylinder, around the cone: a ring of material at each level) had 32 % of its roughing's feed length in air; 9 %
// now, none of the allowance cut (the cone's slope keeps a staircase of more).
TEST(Adaptive, PassesKeepAWayOutOfTheMaterialTheyMeet) {
  job::JobSpec spec = job::read_job(ROSMILL_SOURCE_DIR "/config/jobs/cast_cone.yaml");
  ASSERT_EQ(spec.operations.front().strategy, "rough");
  spec.operations.front().strategy = "adaptive";
  spec.operations.resize(1);
  const job::JobReport r = job::run_job(spec, job_test::options());
  const job::OperationReport& op = r.operations.at(0);
  EXPECT_LT(op.air_cut_share, 0.15);
  EXPECT_LE(op.gouge_mm, 0.0);
  EXPECT_GE(op.min_left_mm, 0.5 - 0.5 * 0.5);  // within the stock's cell
  ASSERT_TRUE(op.engagement_measured);
  EXPECT_LE(op.engagement.max_deg, std::acos(1 - 4.0 / 5.0) * 180 / M_PI + kEngagementSlackDeg);
}

// An open region (the cube's stock margin, entered from the air beside it) and a closed pocket (a helix): cleared
// to the allowance, no gouge, the engagement at the levels within the limit as the verifier measures it.
TEST(Adaptive, OpenAndClosedRegionsClearedAtTheEngagementLimit) {
  const Mesh cube = make_primitive("cube");
  PlanParams open = flat(10, 4, 3, 0.5);
  const Planned a = adaptive(cube, open);
  EXPECT_EQ(a.report.helices, 0u);  // the stock's open sides are the way in
  EXPECT_LE(a.report.max_engagement_deg, a.report.engagement_limit_deg + 2.0);
  EXPECT_NEAR(a.report.engagement_limit_deg, std::acos(1 - 4.0 / 5.0) * 180 / M_PI, 1e-9);
  const Box3 stock = Box3::between(Vec3(-5, -5, 0), Vec3(65, 65, 65));
  EXPECT_LE(measured_level_engagement(a.job, stock), a.report.engagement_limit_deg + kEngagementSlackDeg);
  const verify::VerifyResult va = verified(cube, a.job, stock, 0.5);
  EXPECT_LE(va.report.max_gouge_mm, 0.0);
  EXPECT_EQ(va.report.rapid_cut_cells, 0u);
  // On the top: the allowance (the level at 60.5).
  EXPECT_NEAR(left_on_floor(va, 10, 50, 10, 50, 0), 0.5, 0.01);
  // Turns within the turn radius but at links that turn on the spot (each has two corners).
  EXPECT_LE(sharp_turns(a.job, a.report.min_turn_radius), 2 * a.report.corner_links);

  const Mesh pocket = pocket_block(80, 60, 20, 20, 60, 15, 45, 10);
  const gcode::MachineLimits machine =
      gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine.yaml");
  PlanParams closed = flat(6, 1.2, 5, 0.2);
  closed.stock_margin = 0;
  closed.max_feed = machine.max_feed;  // as `rosmill plan` does with the machine it checks against
  const Planned p = adaptive(pocket, closed);
  EXPECT_GE(p.report.helices, 1u);
  EXPECT_EQ(p.report.ramps, 0u);
  EXPECT_LE(p.report.left_area_mm2, 10.0);  // the pocket's corners, tighter than the turn radius, at 3 levels
  const Box3 block = Box3::between(Vec3(0, 0, 0), Vec3(80, 60, 20));
  EXPECT_LE(measured_level_engagement(p.job, block), p.report.engagement_limit_deg + kEngagementSlackDeg);
  const verify::VerifyResult vp = verified(pocket, p.job, block);
  EXPECT_LE(vp.report.max_gouge_mm, 0.0);
  EXPECT_LE(left_on_floor(vp, 20, 60, 15, 45, 3.5), 0.2 + 0.01);
  EXPECT_LE(sharp_turns(p.job, p.report.min_turn_radius), 2 * p.report.corner_links);
  // The program LinuxCNC's interpreter reads, within the simulator's envelope.
  gcode::ProgramChecks checks;
  checks.machine = machine;
  checks.rs274 = true;
  const gcode::PreparedProgram prepared = gcode::prepare_program(p.job, gcode::post_options_for("linuxcnc"), checks);
  ASSERT_TRUE(prepared.rs274.has_value());
  EXPECT_TRUE(prepared.limits_checked);
}

// A closed channel twice the tool's width round an island (FreeCAD's benchmark region is one): entered by a helix
// and cleared to the allowance by passes across its front, each a step further on (trochoidal), with few passes
// shorter than the stated least and sharp turns only at the links counted as such.
TEST(Adaptive, ClosedChannelClearedByPassesAcrossItsFront) {
  const Mesh groove = ring_groove_block(80, 20, 30, 20, 2);
  PlanParams p = flat(5, 1, 5, 0.2);
  p.stock_margin = 0;
  const Planned a = adaptive(groove, p);
  EXPECT_GE(a.report.helices, 1u);
  EXPECT_LE(a.report.left_area_mm2, 10.0);
  EXPECT_LE(a.report.short_passes, a.report.passes / 10);
  EXPECT_LE(sharp_turns(a.job, a.report.min_turn_radius), 2 * a.report.corner_links);
  const Box3 block = Box3::between(Vec3(0, 0, 0), Vec3(80, 80, 20));
  EXPECT_LE(measured_level_engagement(a.job, block), a.report.engagement_limit_deg + kEngagementSlackDeg);
  const verify::VerifyResult v = verified(groove, a.job, block, 0.25);
  EXPECT_LE(v.report.max_gouge_mm, 0.0);
  for (const auto& [x0, x1, y0, y1] : {std::array<double, 4>{10, 70, 10, 20}, {10, 70, 60, 70}, {10, 20, 20, 60},
                                       {60, 70, 20, 60}})
    EXPECT_LE(left_on_floor(v, x0, x1, y0, y1, 3), 0.2 + 0.01) << x0 << " " << y0;
}

// FreeCAD's Adaptive gives no path at small step-overs: 2 % of the diameter still clears the pocket.
TEST(Adaptive, TwoPercentStepoverStillClears) {
  const Mesh pocket = pocket_block(40, 30, 10, 10, 30, 10, 20, 3);
  PlanParams p = flat(6, 0.12, 3, 0.2);
  p.stock_margin = 0;
  const Planned a = adaptive(pocket, p);
  const Box3 block = Box3::between(Vec3(0, 0, 0), Vec3(40, 30, 10));
  EXPECT_LE(measured_level_engagement(a.job, block), a.report.engagement_limit_deg + kEngagementSlackDeg);
  const verify::VerifyResult v = verified(pocket, a.job, block);
  EXPECT_LE(v.report.max_gouge_mm, 0.0);
  EXPECT_LE(left_on_floor(v, 10, 30, 10, 20, 3.5), 0.2 + 0.01);
}

// FreeCAD's "start point not found" when the tool is large for the pocket: a slot 0.4 mm wider than the tool is
// entered by a ramp along it (no helix fits) and cut to its ends.
TEST(Adaptive, SlotBarelyWiderThanTheToolIsEnteredByARamp) {
  const Mesh slot = pocket_block(60, 30, 10, 10, 50, 9.8, 20.2, 4);
  PlanParams p = flat(10, 4, 4, 0);
  p.stock_margin = 0;
  const Planned a = adaptive(slot, p);
  EXPECT_GE(a.report.ramps, 1u);
  EXPECT_EQ(a.report.helices, 0u);
  const verify::VerifyResult v = verified(slot, a.job, Box3::between(Vec3(0, 0, 0), Vec3(60, 30, 10)));
  EXPECT_LE(v.report.max_gouge_mm, 0.0);
  EXPECT_LE(left_on_floor(v, 15.5, 44.5, 13, 17, 0), 0.01);  // the slot's floor, past the cutter's corners
}

// No level is cut twice, and the first entry starts at the stock's top (FreeCAD's helix started far above it).
TEST(Adaptive, EachLevelOnceAndTheFirstEntryAtTheStocksTop) {
  const Mesh pocket = pocket_block(80, 60, 20, 20, 60, 15, 45, 10);
  PlanParams p = flat(6, 1.2, 4, 0.2);
  p.stock_margin = 0;
  const Planned a = adaptive(pocket, p);
  std::vector<double> levels;
  for (const ToolpathPass& pass : a.job[0].passes) {
    double z = INFINITY;
    for (const Move& m : pass.moves) z = std::min(z, m.to.z());
    levels.push_back(z);
  }
  ASSERT_GE(levels.size(), 3u);
  for (size_t k = 1; k < levels.size(); ++k) EXPECT_LT(levels[k], levels[k - 1]);
  EXPECT_EQ(std::count_if(levels.begin(), levels.end(), [](double z) { return std::abs(z - 10.2) < 1e-9; }), 1)
      << "the pocket's floor plus the allowance";
  // The first move below the stock's top is the helix's first, starting on the top itself.
  const auto& moves = a.job[0].passes[0].moves;
  const auto first_in = std::find_if(moves.begin(), moves.end(), [](const Move& m) { return m.to.z() < 20 - 1e-9; });
  ASSERT_NE(first_in, moves.end());
  ASSERT_NE(first_in, moves.begin());
  EXPECT_NEAR((first_in - 1)->to.z(), 20.0, 1e-9);
  EXPECT_EQ(first_in->type, MoveType::Plunge);
}

// Feeds follow the engagement: where the cutter is in the material less than the tool's stated engagement the
// feed is raised (radial chip thinning), never above the machine's.
TEST(Adaptive, FeedsFollowTheEngagement) {
  const Mesh cube = make_primitive("cube");
  PlanParams p = flat(10, 2, 3, 0.5);
  p.max_feed = 2500;
  const Planned a = adaptive(cube, p);
  double lo = INFINITY, hi = 0;
  for (const ToolpathPass& pass : a.job[0].passes)
    for (const Move& m : pass.moves)
      if (m.type == MoveType::Feed) lo = std::min(lo, m.feed), hi = std::max(hi, m.feed);
  EXPECT_GE(lo, p.tool.feed - 1e-9);  // never slower than the table's feed at its own engagement
  EXPECT_GT(hi, p.tool.feed);
  EXPECT_LE(hi, 2500 + 1e-9);
}

// Rest adaptive: a 6 mm end mill after a 10 mm one works where the 10 mm left more than the allowance and the rest
// threshold (the pocket's corners), not over the whole pocket again: it removes what the 10 mm left there, gouges
// nothing, and cuts a small part of the 10 mm's length. Adaptive follows the job's material, so `rest` changes
// nothing: told or not, it cuts only what is left.
TEST(Adaptive, RestAfterALargerToolTouchesOnlyWhatThatToolLeft) {
  const auto job_with = [](const std::string& rest) {
    return job::parse_job(
        "part: data/pocket.stl\nresolution: 0.5\nstock:\n  mesh: data/pocket_casting.stl\noperations:\n"
        "  - {name: rough, strategy: adaptive, tool: flat:10@1, stepdown: 2, allowance: 0.5}\n"
        "  - {name: rest, strategy: adaptive, tool: flat:6@5, stepdown: 2, allowance: 0.5" + rest + "}\n",
        "rest_adaptive.yaml", ROSMILL_SOURCE_DIR "/config/jobs");
  };
  const job::JobReport r = job::run_job(job_with(", rest: true, rest_threshold: 0.1"), job_test::options());
  const job::JobReport all = job::run_job(job_with(""), job_test::options());
  ASSERT_EQ(r.operations.size(), 2u);
  ASSERT_EQ(all.operations.size(), 2u);
  const job::OperationReport& rough = r.operations[0];
  const job::OperationReport& rest = r.operations[1];
  std::printf("10 mm adaptive: %.0f mm cutting, left %.3f..%.3f mm; 6 mm rest adaptive: %.0f mm cutting, %.0f mm3, "
              "left %.3f..%.3f mm; 6 mm adaptive without rest: %.0f mm cutting, %.0f mm3\n",
              rough.cutting_mm, rough.min_left_mm, rough.max_left_mm, rest.cutting_mm, rest.removed_mm3,
              rest.min_left_mm, rest.max_left_mm, all.operations[1].cutting_mm, all.operations[1].removed_mm3);
  EXPECT_GT(rest.removed_mm3, 0.0);
  EXPECT_LE(rest.gouge_mm, 0.0);
  EXPECT_GE(rest.min_left_mm, -0.001);
  EXPECT_LE(rest.max_left_mm, rough.max_left_mm);
  EXPECT_LT(rest.cutting_mm, 0.1 * rough.cutting_mm);
  // The same material comes off, the same way, whether or not the operation is told to keep to the rest.
  EXPECT_NEAR(rest.removed_mm3, all.operations[1].removed_mm3, 0.05 * all.operations[1].removed_mm3 + 1.0);
  EXPECT_NEAR(rest.cutting_mm, all.operations[1].cutting_mm, 0.05 * all.operations[1].cutting_mm + 1.0);
}

// In a vise: the jaws stand beside the stock, outside the stock's own grid, where adaptive clearing enters from
// the air beside an open side. The job's fixture check (a sweep of the tool's cutter, shank and holder through
// the vise's boxes, code the planner does not share) passes every move, the verifier finds no gouge, and the
// toolpath does come down beside the stock below the jaws' top: the case that had a rapid into the moving jaw.
TEST(Adaptive, InAViseKeepsClearOfTheJawsBesideTheStock) {
  job::JobSpec spec = job::read_job(ROSMILL_SOURCE_DIR "/config/jobs/pocket_sides.yaml");
  spec.setups.resize(2);  // the top and the left
  std::vector<job::OperationSpec> kept;
  for (job::OperationSpec op : spec.operations) {
    if (op.setup_index >= spec.setups.size()) continue;
    if (op.strategy == "rough") op.strategy = "adaptive";
    kept.push_back(op);
  }
  spec.operations = kept;
  job::JobOptions o = job_test::options();
  double lowest_beside = INFINITY;  // the lowest tip beside the stock (outside its x range) in the top's roughing
  o.operation_done = [&](const job::OperationView& v) {
    if (v.index != 0) return;
    const Box3 stock = v.stock.bounds_in(v.setup.frame);
    for (const Toolpath& tp : v.toolpaths)
      for (const ToolpathPass& pass : tp.passes)
        for (const Move& m : pass.moves)
          if (m.to.x() > stock.max.x() || m.to.x() < stock.min.x()) lowest_beside = std::min(lowest_beside, m.to.z());
  };
  const job::JobReport r = job::run_job(spec, o);
  ASSERT_GE(r.operations.size(), 3u);
  EXPECT_EQ(r.operations[0].strategy, "adaptive");
  EXPECT_LE(r.gouge_mm, 0.0);
  EXPECT_GE(r.min_left_mm, -0.001);
  // The jaws grip 4 mm of the 23 mm casting: their top stands 19 mm under the stock's top, the datum.
  EXPECT_LT(lowest_beside, -19.0);
}
