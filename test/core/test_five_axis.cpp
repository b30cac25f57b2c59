// Five-axis finishing with a ball end mill (plan/five_axis_finish.hpp), its tool axes on the trunnion (machine/
// trunnion.hpp indexes_along) and its program for tool-centre-point kinematics, checked against known answers and
// by an independent distance to the mesh (five_axis_check.hpp) that shares no code with the planner.
#include <gtest/gtest.h>

#include <unistd.h>
#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "five_axis_check.hpp"
#include "multi_axis_parts.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/cycle_time.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/geometry/mesh_ray.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/geometry/sphere_sweep.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/machine/trunnion.hpp"
#include "rosmill/plan/five_axis_finish.hpp"
#include "rosmill/plan/four_axis_finish.hpp"
#include "rosmill/plan/tool_axis.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/verify/tool_clearance.hpp"

using namespace rosmill::core;
using five_axis_check::IndependentDistance;
using test_parts::dome_on_plate;

namespace {

constexpr double kDeg = M_PI / 180.0;

PlanParams ball_params(double diameter) {
  PlanParams p;
  p.tool.id = 5;
  p.tool.cutter = Cutter::ball(diameter);
  p.tool.feed = 1000;
  p.tool.plunge_feed = 300;
  p.tool.stepover = 1.0;
  p.tolerance = 0.002;
  return p;
}

// Each cutting move of the toolpath with its tool axis (the tip and axis at the move's end) and the one before.
struct Cut {
  Vec3 from, to, axis_from, axis_to, travel;
};
// `travel`: the pass's direction across the part (its raster line's), from its first cutting move to its last.
std::vector<Cut> cuts(const Toolpath& tp) {
  std::vector<Cut> out;
  for (const ToolpathPass& p : tp.passes) {
    size_t first = 0, last = 0;
    for (size_t k = 1; k < p.moves.size(); ++k)
      if (p.moves[k].type == MoveType::Feed && p.moves[k - 1].type != MoveType::Rapid) {
        if (!first) first = k;
        last = k;
      }
    if (!first) continue;
    Vec3 travel = p.moves[last].to - p.moves[first].to;
    travel.z() = 0;
    for (size_t k = first; k < last; ++k)  // the last feed is the retract up the axis
      out.push_back({p.moves[k - 1].to, p.moves[k].to, p.axes[k - 1], p.axes[k], travel});
  }
  return out;
}

}  // namespace

TEST(SphereSweep, TouchesAtTheRadiusAndNotBefore) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int contacts = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Vec3 o = 3 * Vec3(u(rng), u(rng), u(rng));
    const Vec3 d = Vec3(u(rng), u(rng), u(rng)).normalized();
    const double r = 0.05 + 0.5 * (u(rng) + 1);
    const double t = sphere_sweep_triangle(o, d, r, a, b, c, 0, 10);
    const auto dist = [&](double s) {
      const Vec3 p = o + s * d;
      return (p - five_axis_check::closest_on_triangle(p, a, b, c)).norm();
    };
    if (!std::isfinite(t)) {
      // No contact in [0, 10]: every sampled centre stays out of reach.
      for (int s = 0; s <= 200; ++s) EXPECT_GT(dist(10.0 * s / 200), r - 1e-9);
      continue;
    }
    ++contacts;
    if (t == 0) {
      EXPECT_LE(dist(0), r + 1e-9);
      continue;
    }
    EXPECT_NEAR(dist(t), r, 1e-9) << "contact at t " << t;
    for (int s = 0; s < 50; ++s) EXPECT_GT(dist(t * s / 50), r - 1e-9);
  }
  EXPECT_GT(contacts, 150);
}

TEST(SphereSweep, MeshHierarchyFindsTheFirstContactOfAllFacets) {
  const Mesh mesh = dome_on_plate(20, 30, 8, 48, 16);
  const MeshRays rays(mesh);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 300; ++k) {
    const Vec3 o(30 * u(rng), 30 * u(rng), 40 + 10 * u(rng));
    const Vec3 d = Vec3(0.4 * u(rng), 0.4 * u(rng), -1).normalized();
    double brute = INFINITY;
    for (size_t f = 0; f < mesh.face_count(); ++f)
      brute = std::min(brute,
                       sphere_sweep_triangle(o, d, 3, mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2), 0, 100));
    EXPECT_EQ(rays.first_sphere_contact(o, d, 3, 0, 100), brute);
  }
}

TEST(MeshRays, ARayAlongSharedEdgesAndThroughCornersMeetsTheMesh) {
  // Vertical rays down every meridian of a UV dome, through its facets' shared edges and its corners: each meets
  // the dome on the sphere. Two faults let such rays through to the plate's bottom: the hierarchy's slab test
  // dropped a box whose face the ray ran along when the direction had a -0 (as -UnitZ() has), which lost half the
  // raster line y = 0 of a five-axis finish over this dome; and Moller and Trumbore's test let 191 of these rays
  // slip between the two facets of an edge.
  const double R = 15;
  const Mesh mesh = dome_on_plate(R, 22, 4);
  const MeshRays rays(mesh);
  int missed = 0, rays_cast = 0;
  for (int i = 0; i < 144; ++i)
    for (int j = 0; j <= 200; ++j) {
      const double phi = 2 * M_PI * i / 144, rho = (R - 0.01) * j / 200.0;
      for (const double along : {rho, std::cos(0.5 * M_PI * (j % 48) / 48) * R}) {
        const Vec3 o(along * std::cos(phi), along * std::sin(phi), R + 5);
        ++rays_cast;
        const double t = rays.first_hit(o, -Vec3::UnitZ(), 0, 100);
        if (!std::isfinite(t))
          ++missed;
        else  // on the facets: inside the sphere by a sagitta at most
          EXPECT_NEAR((o - t * Vec3::UnitZ()).norm(), R, 0.02) << o.transpose();
      }
    }
  EXPECT_EQ(missed, 0) << "of " << rays_cast << " rays";
}

TEST(ToolAxis, LeadTurnsTheNormalTowardsTravelAndTheConeHoldsIt) {
  const Vec3 n = Vec3(0.3, -0.2, 1).normalized(), travel(1, 0.5, 0);
  const Vec3 a = lead_tilt_axis(n, travel, 10, 0);
  EXPECT_NEAR(angle_between_deg(a, n), 10, 1e-9);
  const Vec3 f = (travel - travel.dot(n) * n).normalized();
  EXPECT_GT(a.dot(f), 0);
  EXPECT_NEAR(a.dot(n.cross(f)), 0, 1e-12);  // no tilt: in the plane of the normal and the travel
  const Vec3 t = lead_tilt_axis(n, travel, 0, 7);
  EXPECT_NEAR(angle_between_deg(t, n), 7, 1e-9);
  EXPECT_NEAR(t.dot(f), 0, 1e-12);
  const Vec3 flat = within_cone(Vec3(1, 0, 0.1).normalized(), 30);
  EXPECT_NEAR(angle_between_deg(flat, Vec3::UnitZ()), 30, 1e-9);
  EXPECT_NEAR(flat.y(), 0, 1e-12);
  EXPECT_NEAR(angle_between_deg(turn_towards(Vec3::UnitZ(), Vec3::UnitX(), 5), Vec3::UnitZ()), 5, 1e-9);
}

TEST(FiveAxisFinish, DomeAxesAreTheNormalTurnedByTheLeadAndTheBallTouchesTheMesh) {
  const double sphere = 20;
  const Mesh mesh = dome_on_plate(sphere, 30, 8);
  PlanParams p = ball_params(6);
  p.stepover = 2.5;
  p.tool_axis.cone_deg = 60;
  p.tool_axis.rate_deg_per_mm = 20;  // the lead's own turn along a pass, not held back by smoothing
  PlanReport report;
  const Job job = five_axis_finish(mesh, p, {}, &report);
  ASSERT_EQ(job.size(), 1u);
  ASSERT_TRUE(job[0].multi_axis());
  const IndependentDistance distance(mesh);
  const double R = 3, lead = 10;
  // The facets' chords lie inside the true sphere by at most its sagitta: r (1 - cos(half a facet's angle)).
  const double sagitta = sphere * (1 - std::cos(0.5 * M_PI / 144 + 0.25 * M_PI / 48)) * 2;
  int on_dome = 0;
  for (const Cut& c : cuts(job[0])) {
    const Vec3 centre = c.to + R * c.axis_to;
    EXPECT_NEAR(std::abs(c.axis_to.norm() - 1), 0, 1e-12);
    // Exact contact with the mesh, by the independent distance (the ball may stand off it where it meets two
    // facets at once in a concave corner; it never goes in).
    const double dm = distance(centre, R + 1);
    EXPECT_GE(dm, R - 1e-6) << "the ball goes into the mesh at " << c.to.transpose();
    const Vec3 n = centre.normalized();
    if (n.z() < std::cos((60 - lead - 2) * kDeg) || centre.norm() < sphere + R - 0.5) continue;  // off the dome
    ++on_dome;
    EXPECT_NEAR(dm, R, 1e-6) << "a ball on the dome touches it";
    EXPECT_NEAR(centre.norm(), sphere + R, sagitta) << "on the sphere grown by the ball's radius";
    // The axis is the sphere's normal turned by the lead towards travel (the mesh's smooth normal differs from the
    // sphere's by a fraction of a facet's angle).
    const Vec3 expected = lead_tilt_axis(n, c.travel, lead, 0);
    EXPECT_LT(angle_between_deg(c.axis_to, expected), 1.0) << "at " << c.to.transpose();
  }
  EXPECT_GT(on_dome, 500);
  EXPECT_EQ(report.unreachable_points, 0u);
  EXPECT_LE(report.max_tilt_deg, 60 + 1e-9);
}

TEST(FiveAxisFinish, NoGougeOfBallShankOrHolderAlongTheMovesByTheIndependentCheck) {
  // A dome inside a pocket's walls: where the rule's axis would put the holder into a wall, the axis turns.
  const Mesh mesh = test_parts::dome_between_walls();
  PlanParams p = ball_params(6);
  p.stepover = 3;
  p.tool.stick_out = 26;
  p.tool.holder_diameter = 20;
  p.tool_axis.cone_deg = 45;
  PlanReport report;
  const Job job = five_axis_finish(mesh, p, {}, &report);
  ASSERT_EQ(job.size(), 1u);
  EXPECT_GT(report.axes_turned_to_clear, 0u) << "the walls turn some axes";
  // Ball, flutes, shank and holder at every move's end and middle (tip and axis interpolated), by the exact distance
  // planning does not use.
  const verify::ToolClearance c = verify::check_tool_clearance(mesh, job, p.allowance);
  EXPECT_GT(c.positions, 1000u);
  EXPECT_LE(c.ball_depth_mm, p.tolerance) << c.deepest;
  EXPECT_LE(c.body_depth_mm, p.tolerance + c.sampling_mm) << c.deepest;
  // The check sees a gouge: the same toolpath 0.05 mm down goes in by that much.
  Job lower = job;
  for (ToolpathPass& pass : lower[0].passes)
    for (Move& m : pass.moves) m.to.z() -= 0.05;
  EXPECT_NEAR(verify::check_tool_clearance(mesh, lower, p.allowance).ball_depth_mm, 0.05, 0.01);
}

// A prismatic part with features on five sides (a pocket with an island, a step, a slot, holes, a groove), finished
// from above in five axes as a new user would (`rosmill plan five_sided.stl --strategy five-axis --tool ball:6`):
// sharp convex edges and walls the cone's edge meets. No part of the tool goes into the part between the cutter
// locations either, by the independent check.
TEST(FiveAxisFinish, APrismaticPartWithFeaturesOnFiveSidesIsFinishedClear) {
  const Mesh mesh = read_stl(std::string(ROSMILL_SOURCE_DIR) + "/test/data/parts/five_sided.stl");
  PlanParams p = ball_params(6);
  p.tolerance = 0.001;  // the default's
  PlanReport report;
  const Job job = five_axis_finish(mesh, p, {}, &report);
  ASSERT_EQ(job.size(), 1u);
  const verify::ToolClearance c = verify::check_tool_clearance(mesh, job, p.allowance);
  EXPECT_GT(c.positions, 1000u);
  EXPECT_LE(c.ball_depth_mm, p.tolerance) << c.deepest;
  EXPECT_LE(c.body_depth_mm, p.tolerance + c.sampling_mm) << c.deepest;
}

TEST(FiveAxisFinish, RefusesAFlatEndMill) {
  PlanParams p = ball_params(6);
  p.tool.cutter = Cutter::flat(6);
  const Mesh mesh = dome_on_plate(10, 15, 4, 24, 8);
  try {
    five_axis_finish(mesh, p, {});
    FAIL() << "a flat end mill was planned";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ball end mill"), std::string::npos) << e.what();
  }
}

namespace {
const machine::Trunnion& tcp_trunnion() {
  static const gcode::MachineLimits m =
      gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine_xyzac_tcp.yaml");
  return *m.trunnion;
}
}  // namespace

TEST(IndexesAlong, EveryTurnBringsItsAxisOntoTheSpindle) {
  std::vector<Vec3> axes;
  for (int k = 0; k <= 60; ++k)
    axes.push_back(Vec3(std::sin(40 * kDeg) * std::cos(k * 6 * kDeg), std::sin(40 * kDeg) * std::sin(k * 6 * kDeg),
                        std::cos(40 * kDeg)));
  const auto turns = machine::indexes_along(tcp_trunnion(), axes, {});
  ASSERT_TRUE(turns);
  for (size_t k = 0; k < axes.size(); ++k)
    EXPECT_LT((tcp_trunnion().tool_axis((*turns)[k].a, (*turns)[k].c) - axes[k]).norm(), 1e-12);
  // A full circle about +Z: C winds a whole turn, never wrapped, A holds.
  EXPECT_NEAR(std::abs((*turns).back().c - (*turns).front().c), 360, 1e-9);
  for (size_t k = 1; k < axes.size(); ++k) {
    EXPECT_NEAR((*turns)[k].a, (*turns)[0].a, 1e-9);
    EXPECT_LT(std::abs((*turns)[k].c - (*turns)[k - 1].c), 6 + 1e-9);
  }
}

TEST(IndexesAlong, ThePoleIsCrossedByAWithoutAHalfTurnOfC) {
  // Through the pole: from 20 degrees towards -Y to 20 degrees towards +Y in the YZ plane, and past it at 1 degree.
  // Exactly through it A changes sign and C stays; passing it at a degree the axis's azimuth turns half a turn in a
  // few steps, which C must follow in either branch, but never more.
  for (const double miss : {0.0, 1.0}) {
    SCOPED_TRACE("passing the pole at " + std::to_string(miss) + " degrees");
    std::vector<Vec3> axes;
    for (int k = -20; k <= 20; ++k)
      axes.push_back((Eigen::AngleAxisd(miss * kDeg, Vec3::UnitY()) * Eigen::AngleAxisd(-k * kDeg, Vec3::UnitX()) *
                      Vec3::UnitZ()));
    const auto turns = machine::indexes_along(tcp_trunnion(), axes, {});
    ASSERT_TRUE(turns);
    double most_c = 0, total_c = 0;
    for (size_t k = 1; k < axes.size(); ++k) {
      most_c = std::max(most_c, std::abs((*turns)[k].c - (*turns)[k - 1].c));
      total_c += std::abs((*turns)[k].c - (*turns)[k - 1].c);
    }
    if (miss == 0) {
      EXPECT_LT(most_c, 1e-9) << "C turns " << most_c << " degrees in one step";
      EXPECT_LT((*turns).front().a * (*turns).back().a, 0) << "A changes sign at the pole";
    } else {
      EXPECT_LT(total_c, 180 + 1e-6) << "C turns " << total_c << " degrees in all";
    }
    for (size_t k = 0; k < axes.size(); ++k)
      EXPECT_LT((tcp_trunnion().tool_axis((*turns)[k].a, (*turns)[k].c) - axes[k]).norm(), 1e-9);
  }
}

TEST(IndexesAlong, AnAxisOutsideARangeIsNamed) {
  std::string why;
  // 120 degrees from +Z: A = +-120, outside [-100, 50].
  const auto turns = machine::indexes_along(
      tcp_trunnion(), {Vec3::UnitZ(), Vec3(std::sin(120 * kDeg), 0, std::cos(120 * kDeg))}, {}, &why);
  EXPECT_FALSE(turns);
  EXPECT_NE(why.find("tool axis 1"), std::string::npos) << why;
  EXPECT_NE(why.find("[-100, 50]"), std::string::npos) << why;
}

namespace {

Job dome_job() {
  PlanParams p = ball_params(6);
  p.stepover = 4;
  p.tool_axis.cone_deg = 45;
  return five_axis_finish(dome_on_plate(12, 16, 5, 72, 24), p, {});
}

gcode::PostOptions tcp_post() {
  return gcode::with_tool_centre_point(
      {}, gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine_xyzac_tcp.yaml"), "test");
}

}  // namespace

TEST(ToolCentrePointProgram, PassesTheLimitsAndLinuxcncsInterpreterWithTheAxesItWasPlannedWith) {
  const Job job = dome_job();
  gcode::ProgramChecks checks;
  checks.machine = gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine_xyzac_tcp.yaml");
  checks.limits.stock_top = 12;
  checks.rs274 = ::access("/usr/bin/rs274", X_OK) == 0;
  const gcode::PreparedProgram prepared = gcode::prepare_program(job, tcp_post(), checks);
  const auto& lines = prepared.program.lines;
  EXPECT_TRUE(prepared.limits_checked);
  if (prepared.rs274) {
    EXPECT_TRUE(prepared.rs274->ok) << prepared.rs274->problem;
  }
  // Every move's A and C, as the program's reader follows them, turn the spindle onto the toolpath's axis there.
  gcode::Interpreter reader;
  size_t compared = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    reader.read(lines[i], i + 1);
    const gcode::LineOrigin& o = prepared.program.origin[i];
    if (!reader.moved() || o.first_move < 0) continue;
    const Vec3 axis = tcp_trunnion().tool_axis(reader.move().a_to, reader.move().c_to);
    const Vec3& planned = job[o.toolpath].passes[o.pass].axes[o.last_move];
    EXPECT_LT(angle_between_deg(axis, planned), 2e-4) << "line " << i + 1 << ": " << lines[i];
    ++compared;
  }
  EXPECT_GT(compared, 200u);
  // The kinematics switches are in the program, around its moves.
  EXPECT_NE(std::find(lines.begin(), lines.end(), "M428"), lines.end());
  EXPECT_EQ(std::count(lines.begin(), lines.end(), "M429"), 2);
}

TEST(ToolCentrePointProgram, RefusedWithoutToolCentrePointControl) {
  const Job job = dome_job();
  gcode::PostOptions o = tcp_post();
  o.trunnion->mode = machine::KinematicsMode::Identity;
  EXPECT_THROW(gcode::post(job, o), Error);
  o.trunnion.reset();
  EXPECT_THROW(gcode::post(job, o), Error);
  // A program that switches to tool-centre-point kinematics on a machine set up for identity: refused by the check.
  const gcode::MachineLimits identity =
      gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine_xyzac.yaml");
  const std::vector<gcode::LimitViolation> v =
      gcode::check_limits({"G21 G90 G54", "M428", "G0 X0 Y0 Z50 A0 C0"}, identity);
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v.front().limit, "kinematics");
  // On a mill with no rotary axes at all, the same, and the moves after it checked as they read.
  const gcode::MachineLimits mill = gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine.yaml");
  const std::vector<gcode::LimitViolation> w =
      gcode::check_limits({"G21 G90 G54", "M428", "G0 X0 Y0 Z50", "G1 X10 Y10 Z40 A10 C20 F500"}, mill);
  ASSERT_GE(w.size(), 2u);
  EXPECT_EQ(w[0].limit, "kinematics");
  EXPECT_EQ(w[1].limit, "rotary axes");
}

TEST(ToolCentrePointProgram, TheJointsOfAMoveStayInTheEnvelope) {
  // On the table the tip moves 10 mm; with A at -90 the machine's Z joint swings far: machine_point of the tip.
  const gcode::MachineLimits m =
      gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine_xyzac_tcp.yaml");
  gcode::LimitCheckOptions o;
  o.stock_top = 0;
  const std::vector<std::string> ok = {"G21 G90 G54", "M428", "G0 X0 Y0 Z40 A0 C0", "G1 X0 Y5 Z40 A-20 C0 F100"};
  for (const gcode::LimitViolation& v : gcode::check_limits(ok, m, o)) ADD_FAILURE() << v.message();
  // The same at F500: 6.4 mm of tip in 0.77 s, while A's turn of 20 degrees swings the table's point 40 mm over
  // the pivot through some 20 mm: machine Y at 27 mm/s, over its 20.
  std::vector<std::string> fast = ok;
  fast.back() = "G1 X0 Y5 Z40 A-20 C0 F500";
  const std::vector<gcode::LimitViolation> f = gcode::check_limits(fast, m, o);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f.front().limit, "joint y speed");
  // Y 150 on the table at A -60: machine z = 150 sin 60 + ... above 120.
  const std::vector<std::string> out = {"G21 G90 G54", "M428", "G0 X0 Y0 Z40 A0 C0", "G1 X0 Y-150 Z40 A-60 C0 F500"};
  const std::vector<gcode::LimitViolation> v = gcode::check_limits(out, m, o);
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v.front().line, 4u);
  EXPECT_NE(v.front().limit.find("envelope"), std::string::npos) << v.front().message();
}

TEST(ToolCentrePointProgram, AMoveThatTurnsTheTableIsBoundByTheRotaryAxes) {
  // Exact stop (G61): 10 mm of tip at 600 mm/min with A turning 10 degrees: 30 deg/s allows 10 mm/s, the feed
  // 10 mm/s; the accelerations (300 mm/s^2, 300 deg/s^2 = 300 mm/s^2 at 1 deg/mm) ramp in and out: 10/10 + 10/300 s.
  gcode::TrajectoryLimits lim;
  lim.max_velocity = Vec3(20, 20, 20);
  lim.max_acceleration = Vec3(300, 300, 300);
  lim.rotary_velocity = Vec2(30, 30);
  lim.rotary_acceleration = Vec2(300, 300);
  const gcode::CycleTime t =
      gcode::estimate_cycle_time({"G21 G90 G54 G61", "G1 X0 Y0 Z0 A0 C0 F600", "G1 Y10 A10", "G1 Y20 A20"}, lim);
  EXPECT_NEAR(t.motion_seconds, 2 * (1.0 + 10.0 / 300), 1e-6);
  // Blended (G64), ten short moves run on through their ends, parabolically at half the acceleration (LinuxCNC
  // makes no blend arc where a rotary axis turns), in less time than stopping at each; never faster than the
  // rotary axis allows (C at 30 deg/s over 30 degrees: 1 s).
  std::vector<std::string> program = {"G21 G90 G54 G64 P0.01", "G1 X0 Y0 Z0 A0 C0 F600"};
  for (int k = 1; k <= 10; ++k) program.push_back("G1 Y" + std::to_string(k) + " C" + std::to_string(3 * k));
  const double blended = gcode::estimate_cycle_time(program, lim).motion_seconds;
  program[0] = "G21 G90 G54 G61";
  const double stopped = gcode::estimate_cycle_time(program, lim).motion_seconds;
  EXPECT_LT(blended, 0.9 * stopped) << blended << " s blended, " << stopped << " s stopping";
  EXPECT_GT(blended, 1.0);
}

TEST(FourAxisFinish, ACylindersSideIsCutWithTheAxisAcrossItAndTheTableFollowsTheAngle) {
  const double r = 15, R = 3;
  const int segments = 180;
  const Mesh mesh = test_parts::cylinder_standing(r, 50, segments);
  PlanParams p = ball_params(6);
  p.stepover = 5;
  p.tool_axis.lead_deg = 0;
  PlanReport report;
  const Job job = four_axis_finish(mesh, p, {}, &report);
  ASSERT_EQ(job.size(), 1u);
  const IndependentDistance distance(mesh);
  const double sagitta = r * (1 - std::cos(M_PI / segments));
  size_t cut = 0;
  std::vector<Vec3> axes;
  for (const ToolpathPass& pass : job[0].passes)
    for (size_t k = 0; k < pass.moves.size(); ++k) {
      axes.push_back(pass.axes[k]);
      if (pass.moves[k].type != MoveType::Feed || k + 1 == pass.moves.size() || k < 2) continue;
      const Vec3& axis = pass.axes[k];
      const Vec3 centre = pass.moves[k].to + R * axis;
      const Vec3 radial = Vec3(centre.x(), centre.y(), 0).normalized();
      EXPECT_NEAR(axis.z(), 0, 1e-12) << "the axis across the rotary axis";
      EXPECT_LT(angle_between_deg(axis, radial), 0.5) << "radial at " << centre.transpose();
      EXPECT_NEAR(Vec2(centre.x(), centre.y()).norm(), r + R, sagitta + 1e-6);
      EXPECT_GE(distance(centre, R + 1), R - 1e-6);
      ++cut;
    }
  EXPECT_GT(cut, 1000u);
  EXPECT_EQ(report.unreachable_points, 0u);
  // On the trunnion A holds at -90 degrees (the part's axis level) and C follows the angle round each ring.
  const auto turns = machine::indexes_along(tcp_trunnion(), axes, {});
  ASSERT_TRUE(turns);
  for (size_t k = 0; k < axes.size(); ++k) {
    EXPECT_NEAR((*turns)[k].a, -90, 1e-6);
    if (k > 0) {
      EXPECT_LT(std::abs((*turns)[k].c - (*turns)[k - 1].c), 5.0) << "C jumps at " << k;
    }
  }
  // The program passes the limits (the joints all along) and LinuxCNC's interpreter.
  gcode::ProgramChecks checks;
  checks.machine = gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine_xyzac_tcp.yaml");
  checks.limits.stock_top = 50;
  checks.rs274 = ::access("/usr/bin/rs274", X_OK) == 0;
  const gcode::PreparedProgram prepared = gcode::prepare_program(job, tcp_post(), checks);
  if (prepared.rs274) {
    EXPECT_TRUE(prepared.rs274->ok) << prepared.rs274->problem;
  }
}
