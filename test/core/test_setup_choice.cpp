// Setup selection (setups/setup_choice.hpp): known answers on parts whose best setups a machinist can count (the
// cube held on its bottom, the cavity, an undercut whose area is known in closed form), what the tool reaches checked
// against the independent reference drop-cutter, the fixture's hidden area, and the choice against a brute-force
// search written here over every set of candidates on every bundled model.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "bundled_models.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/segment/surface_patches.hpp"
#include "rosmill/setups/setup_choice.hpp"
#include "rosmill/testing/exhaustive_cover.hpp"
#include "rosmill/testing/reference_drop.hpp"
#include "rosmill/testing/sanitized.hpp"

using namespace rosmill::core;
using namespace rosmill::core::setups;

namespace {

// The finishing ball of the package's tool table: 6 mm, 20 mm of flutes, 30 mm out of a 28 mm holder.
Tool finishing_ball() {
  static const ToolTable tools = read_tool_table(std::string(ROSMILL_SOURCE_DIR) + "/config/tools.yaml");
  return tools.get(2);
}

SetupChoice choose(const Mesh& part, ChoiceOptions o) {
  const segment::SurfacePatches sp = segment::segment_surface(part);
  return choose_setups(part, sp, o);
}

ChoiceOptions with_tool(const Tool& tool) {
  ChoiceOptions o;
  o.tool = tool;
  return o;
}

std::vector<std::string> names(const SetupChoice& c) {
  std::vector<std::string> n;
  for (const ChosenSetup& s : c.setups) n.push_back(s.name);
  return n;
}

double unreached(const SetupChoice& c, const std::string& reason) {
  double a = 0;
  for (const Unreached& u : c.unreachable) a += u.reason == reason ? u.area : 0.0;
  return a;
}

// A solid of revolution about Z from a closed profile of (r, z) points, walked so that the material lies to the
// left (outward normals), with `n` segments; points at r = 0 close the surface there.
Mesh revolved(const std::vector<Vec2>& profile, int n) {
  std::vector<Vec3> c;
  auto at = [&](const Vec2& p, int k) {
    const double a = 2 * M_PI * (k % n) / n;
    return Vec3(p.x() * std::cos(a), p.x() * std::sin(a), p.y());
  };
  for (size_t i = 0; i < profile.size(); ++i) {
    const Vec2 &p = profile[i], &q = profile[(i + 1) % profile.size()];
    for (int k = 0; k < n; ++k) {
      const Vec3 p0 = at(p, k), p1 = at(p, k + 1), q0 = at(q, k), q1 = at(q, k + 1);
      if (p.x() > 0) c.insert(c.end(), {p0, q0, p1});
      if (q.x() > 0) c.insert(c.end(), {p1, q0, q1});
    }
  }
  Mesh m = build_mesh(c);
  if (report(m).volume < 0) {  // walked the other way round: turn every triangle over
    for (size_t k = 0; k < c.size(); k += 3) std::swap(c[k + 1], c[k + 2]);
    m = build_mesh(c);
  }
  return m;
}

// A round block (r 30, 30 high) with a hole (r 10) from the top into a wider chamber (r 15, 5 high, 15 deep): the
// chamber's ceiling, its wall and the floor under the ceiling are an undercut no 3-axis setup reaches.
Mesh undercut_part(int n) {
  return revolved({{0, 0}, {30, 0}, {30, 30}, {10, 30}, {10, 15}, {15, 15}, {15, 10}, {10, 10}, {0, 10}}, n);
}

// Area of the ring between radii a and b of the n-gon, and of the n-gon prism's side of radius r and height h.
double ring_area(double a, double b, int n) { return 0.5 * n * std::sin(2 * M_PI / n) * (b * b - a * a); }
double prism_side(double r, double h, int n) { return n * 2 * r * std::sin(M_PI / n) * h; }

}  // namespace

// The cube held on its bottom face (a fixture plate): each of its five other faces is reached whole only from
// the direction it faces (the 6 mm ball reaches 27 mm down a wall past its holder, the cube stands 60 mm), so
// exactly five setups, and the bottom's 3600 mm^2 is what no setup machines.
TEST(SetupChoice, CubeHeldOnItsBottomNeedsFiveSetups) {
  ChoiceOptions o = with_tool(finishing_ball());
  o.held_face = Vec3(0, 0, -1);
  const SetupChoice c = choose(make_primitive("cube"), o);
  EXPECT_EQ(names(c), (std::vector<std::string>{"+Z", "+X", "-X", "+Y", "-Y"}));
  EXPECT_TRUE(c.exhaustive);
  EXPECT_NEAR(c.unreachable_area, 3600.0, 1e-6);
  EXPECT_NEAR(unreached(c, "held"), 3600.0, 1e-6);
  for (const ChosenSetup& s : c.setups) {
    EXPECT_NEAR(s.assigned_area, 3600.0, 1e-6) << s.name;
    ASSERT_EQ(s.segments.size(), 1u) << s.name;
    EXPECT_GT(s.segments[0].normal.dot(s.direction), 0.999) << s.name;
    // Each reaches its own face and the top 27 mm of the four faces around it (60 mm wide), no more.
    EXPECT_NEAR(s.reachable_area, 3600.0 + (s.name == "+Z" ? 4 : 3) * 60.0 * 27.0, 60.0 * 4) << s.name;
  }
  // Not held, the bottom takes a sixth setup.
  EXPECT_EQ(choose(make_primitive("cube"), with_tool(finishing_ball())).setups.size(), 6u);
}

// The cavity primitive (a hemispherical pocket in a round block 60 high) held on its bottom: a tool whose holder
// clears the block's 60 mm walls reaches all the rest from +Z alone. With the table's 30 mm stick-out the walls'
// lower half needs the part turned.
TEST(SetupChoice, CavityFromAboveAlone) {
  Tool long_ball = finishing_ball();
  long_ball.stick_out = 70;
  ChoiceOptions o = with_tool(long_ball);
  o.held_face = Vec3(0, 0, -1);
  const Mesh cavity = make_primitive("cavity");
  const SetupChoice c = choose(cavity, o);
  EXPECT_EQ(names(c), std::vector<std::string>{"+Z"});
  EXPECT_NEAR(c.unreachable_area, unreached(c, "held"), 1e-9);
  EXPECT_NEAR(c.machined_area + c.unreachable_area, c.total_area, 1e-6 * c.total_area);
  o.tool = finishing_ball();
  EXPECT_GT(choose(cavity, o).setups.size(), 1u);
}

// The undercut: reported unreachable with its area, the n-gon's exact one.
TEST(SetupChoice, UndercutReportedWithItsArea) {
  const int n = 72;
  const Mesh part = undercut_part(n);
  ChoiceOptions o = with_tool(finishing_ball());
  o.held_face = Vec3(0, 0, -1);
  const SetupChoice c = choose(part, o);
  const double undercut = 2 * ring_area(10, 15, n) + prism_side(15, 5, n);
  EXPECT_NEAR(unreached(c, "unreachable"), undercut, 0.005 * undercut);
  EXPECT_NEAR(unreached(c, "held"), ring_area(0, 30, n), 1e-6);
  // Everything else is machined: the top, the hole, the floor under it and the block's side.
  EXPECT_NEAR(c.machined_area, c.total_area - undercut - ring_area(0, 30, n), 0.005 * undercut);
  // Every place reported lies in the chamber (between radii 10 and 15, heights 10 to 15) or on the bottom.
  for (const Unreached& u : c.unreachable) {
    if (u.reason == "held") continue;
    const double r = u.centroid.head<2>().norm();
    EXPECT_TRUE(r < 15.01 && u.centroid.z() > 9.99 && u.centroid.z() < 15.01)
        << u.reason << " at " << u.centroid.transpose();
  }
}

// What the product finds reached, hidden or facing away agrees with the reference drop-cutter (a vertical line over
// the sample, the shank and the holder asked as flat cutters of their diameters, the part turned into the setup),
// within a hair of the heights either way.
TEST(SetupChoice, ReachAgreesWithTheReferenceDropCutter) {
  const Mesh parts[] = {undercut_part(24), read_stl(std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/data/pocket.stl")};
  const Tool tool = finishing_ball();
  const ReachTool t = reach_tool(tool);
  std::mt19937 random(7);
  for (const Mesh& part : parts) {
    const SurfaceSamples s = sample_surface(part, sample_spacing(part, 3000));
    std::vector<size_t> picks;
    for (int k = 0; k < rosmill::testing::cases(200, 40); ++k) picks.push_back(random() % s.size());
    for (const char* name : {"+Z", "-Z", "+X", "-Y"}) {
      const SetupFrame setup = named_setup(name);
      const Mesh turned = placed(part, setup.placement);
      const std::vector<Reach> reach = reach_along(part, s, setup, t, {});
      for (const size_t k : picks) {
        const Vec3 n = setup.direction_to_setup(s.normals[k]), p = setup.to_setup_frame(s.points[k]);
        if (n.z() < -1e-9) {
          EXPECT_EQ(reach[k], Reach::FacesAway);
          continue;
        }
        // Blocked by the reference when something stands above `z` within `radius` of (x, y), by `margin`.
        auto blocked = [&](double radius, const Vec2& at, double z, double margin) {
          return reference_drop(Cutter::flat(2 * radius), turned, at.x(), at.y()) > z + margin;
        };
        const double s_xy = n.head<2>().norm();
        Vec2 axis = p.head<2>();
        if (s_xy > 1e-9) axis += t.corner_radius * n.head<2>() + (t.radius - t.corner_radius + 0.01) * n.head<2>() / s_xy;
        const double tip = p.z() + t.corner_radius * (n.z() - 1);
        const Vec3 q = p + 0.01 * n;
        const auto reference = [&](double margin) {
          return blocked(0.001, q.head<2>(), q.z(), margin) ||
                 blocked(t.shank_radius, axis, tip + t.flute_length, margin) ||
                 blocked(t.holder_radius, axis, tip + t.stick_out, margin);
        };
        if (reach[k] == Reach::Reached) EXPECT_FALSE(reference(1e-6)) << name << " sample " << k;
        else EXPECT_TRUE(reference(-1e-6)) << name << " sample " << k;
      }
    }
  }
}

// A vise gripping the pocket part's y faces 5 mm up: from +Z alone, the bottom 5 mm of those two walls (50 mm long)
// is reachable but for the jaws.
TEST(SetupChoice, AreaHiddenByTheFixtureIsReportedAsSuch) {
  const Mesh part = read_stl(std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/data/pocket.stl");
  ChoiceOptions o = with_tool(finishing_ball());
  o.held_face = Vec3(0, 0, -1);
  o.directions = {Vec3::UnitZ()};
  fixture::FixtureSpec vise;
  vise.kind = fixture::FixtureSpec::Kind::Vise;
  vise.vise.grip = 5;
  vise.vise.clamp = 'y';
  o.fixture = vise;
  o.spacing = 0.2;
  const SetupChoice c = choose(part, o);
  ASSERT_EQ(names(c), std::vector<std::string>{"+Z"});
  // Within a row of samples along each wall: the jaws' top cuts through the samples' little triangles.
  EXPECT_NEAR(unreached(c, "fixture"), 2 * 50.0 * 5.0, 2 * 50.0 * o.spacing);
  // Without the vise those walls are machined whole.
  o.fixture.reset();
  EXPECT_NEAR(choose(part, o).unreachable_area, 50.0 * 40.0, 1e-6);
  // A vise that does not open wide enough for the part in a direction refuses that candidate, with the reason.
  vise.vise.opening = 30;
  o.fixture = vise;
  o.directions = {Vec3::UnitZ(), Vec3::UnitX()};
  const SetupChoice narrow = choose(part, o);
  for (size_t k = 0; k < narrow.candidates.size(); ++k)
    EXPECT_NE(narrow.candidate_refused[k].find("the vise opens 30 mm"), std::string::npos) << narrow.candidates[k].name;
  EXPECT_TRUE(narrow.setups.empty());
}

// The choice against a brute force (test support's exhaustive_cover, apart from the search's code): every set of
// candidates, the fewest whose cover under the rule (a face reached whole by one setup counts only whole; other
// surface where any setup reaches it) comes within the least gain of all candidates', and the largest cover among
// those. On every bundled model.
TEST(SetupChoice, TheChoiceIsTheBestOfEverySetOfCandidates) {
  std::vector<std::pair<std::string, Mesh>> models = {{"cube", make_primitive("cube")},
                                                      {"cavity", make_primitive("cavity")},
                                                      {"undercut", undercut_part(36)}};
  for (const test_data::BundledModel& m : test_data::kBundledModels) {
    if (!m.small) continue;
    StlReadOptions read;
    read.units = m.units;
    models.emplace_back(m.file, read_stl(std::string(ROSMILL_TEST_DATA) + "/" + m.file, read));
  }
  for (const auto& [name, part] : models) {
    const segment::SurfacePatches sp = segment::segment_surface(part);
    ChoiceOptions o = with_tool(finishing_ball());
    o.spacing = sample_spacing(part, rosmill::testing::cases(8000, 2000));
    const SetupChoice c = choose_setups(part, sp, o);
    ASSERT_LE(c.candidates.size(), 16u) << name;
    uint64_t chosen = 0;
    for (const ChosenSetup& s : c.setups) chosen |= uint64_t(1) << s.candidate;
    const rosmill::core::testing::ExhaustiveCover e =
        rosmill::core::testing::exhaustive_cover(c, sp, o.min_gain_share * c.total_area, chosen);
    EXPECT_EQ(c.setups.size(), e.fewest) << name;
    EXPECT_NEAR(e.of_chosen, e.best, 1e-6 * c.total_area) << name;
    EXPECT_NEAR(c.best_cover, e.all, 1e-6 * c.total_area) << name;
    std::printf("%-22s %zu candidates, %zu setups chosen, cover %.1f of %.1f mm^2 (all candidates %.1f)\n",
                name.c_str(), c.candidates.size(), c.setups.size(), e.of_chosen, c.total_area, e.all);
  }
}

TEST(SetupChoice, BadOptionsAreRefused) {
  const Mesh cube = make_primitive("cube");
  ChoiceOptions o = with_tool(finishing_ball());
  o.min_gain_share = 1.5;
  EXPECT_THROW(choose(cube, o), Error);
  o = with_tool(finishing_ball());
  o.tool.stick_out = 1;  // shorter than its flutes
  EXPECT_THROW(choose(cube, o), Error);
  o = with_tool(finishing_ball());
  o.directions = {Vec3(0, 0, 0)};
  EXPECT_THROW(choose(cube, o), Error);
  o.directions = {Vec3(NAN, 0, 1)};
  EXPECT_THROW(choose(cube, o), Error);
}

// The room of the default machine (config/machine.yaml: LinuxCNC's 3-axis sim) for a stock in a vise: the tip's Z
// travel ends at 101.6 over a table at -50, the X and Y travel at +-254.
TEST(SetupChoice, AStockTooTallOrTooLongForTheMachineDoesNotFit) {
  MachineRoom room;
  room.travel = Box3::between(Vec3(-254, -254, -50.8), Vec3(254, 254, 101.6));
  room.table_z = -50;
  room.clearance = 5;
  room.beyond = 11;
  room.name = "linuxcnc-sim-mm";
  fixture::FixtureSpec vise;
  vise.kind = fixture::FixtureSpec::Kind::Vise;
  const auto misfit = [&](const Vec3& size) {
    const Box3 stock = Box3::between(Vec3::Zero(), size);
    return machine_misfit(room, stock, fixture::place_fixture(vise, stock, "vise"));
  };
  // 44 mm high stands on the vise's seat (its floor and parallels, 30 + 20 mm) and clears with its 5 mm: z 49.
  EXPECT_EQ(misfit(Vec3(100, 50, 44)), "");
  // 183 mm high (a 178 mm part on its end): the tip would reach 188.
  const std::string tall = misfit(Vec3(50, 40, 183));
  EXPECT_NE(tall.find("machine z 188.0, above linuxcnc-sim-mm's Z travel (101.6)"), std::string::npos) << tall;
  // 500 mm long along x: with the tools 11 mm beyond it, from -261 to 261.
  const std::string along = misfit(Vec3(500, 40, 30));
  EXPECT_NE(along.find("along x"), std::string::npos) << along;
  EXPECT_NE(along.find("-261.0 to 261.0"), std::string::npos) << along;
}

// A direction the machine cannot take (a trunnion whose A axis stops short of turning the part over) is no setup:
// what of the cube's bottom only -Z reaches is left for want of a machine that does, with the machine's reason.
TEST(SetupChoice, ADirectionTheMachineCannotTakeIsNoSetup) {
  ChoiceOptions o = with_tool(finishing_ball());
  o.direction_refused = [](const Vec3& d) {
    return d.z() < -0.5 ? std::string("this machine cannot index the part for it: A would be 180") : std::string();
  };
  const SetupChoice c = choose(make_primitive("cube"), o);
  EXPECT_EQ(names(c), (std::vector<std::string>{"+Z", "+X", "-X", "+Y", "-Y"}));
  // The side setups reach the bottom as a wall, 27 mm in from each edge (as in CubeHeldOnItsBottomNeedsFiveSetups):
  // its middle 6 x 6 mm only -Z reaches (to the samples' spacing).
  EXPECT_NEAR(unreached(c, "machine"), 36.0, 6.0);
  bool refused = false;
  for (size_t k = 0; k < c.candidates.size(); ++k)
    if (c.candidates[k].direction.z() < -0.5) {
      refused = true;
      EXPECT_TRUE(c.candidate_unfit[k]);
      EXPECT_EQ(c.candidate_refused[k], "this machine cannot index the part for it: A would be 180");
    }
  EXPECT_TRUE(refused);
}
