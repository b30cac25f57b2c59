// Fixtures (fixture/fixture.hpp): a vise, parallels and clamps placed around the stock by their rule, bad ones
// refused with the reason; and the fixture in the stock's collision world (stock/fixture_collision.hpp): which part
// of the tool enters which box at which move, the exact sweep checked against positions sampled densely along the
// moves.
#include <gtest/gtest.h>

#include <random>

#include "error_of.hpp"
#include "rosmill/error.hpp"
#include "rosmill/fixture/fixture.hpp"
#include "rosmill/stock/fixture_collision.hpp"

using namespace rosmill::core;
using namespace rosmill::core::fixture;

namespace {

const FixtureBox& named(const Fixture& f, const std::string& name) {
  for (const FixtureBox& b : f.boxes)
    if (b.name == name) return b;
  throw Error("test", "no box " + name);
}

Tool ball6() {
  Tool t;
  t.cutter = Cutter::ball(6);
  t.cutter.flute_length = 20;
  t.stick_out = 30;
  t.holder_diameter = 28;
  return t;
}

stock::MachineProgram program(const std::vector<std::pair<Vec3, Vec3>>& moves, bool rapid = false) {
  stock::MachineProgram p;
  p.tools.push_back(ball6());
  uint32_t n = 0;
  for (const auto& [a, b] : moves) {
    CanonMove m;
    m.from = a;
    m.to = b;
    m.rapid = rapid;
    m.source = ++n;
    p.moves.push_back(m);
  }
  return p;
}

}  // namespace

TEST(Fixture, ViseGripsTheStockByTheRule) {
  // A stock 54 x 44 x 23 mm, the vise's jaws closing along y.
  const Box3 stock = Box3::between(Vec3(-2, -2, 0), Vec3(52, 42, 23));
  FixtureSpec spec;
  spec.kind = FixtureSpec::Kind::Vise;
  spec.vise.grip = 5;
  const Fixture f = place_fixture(spec, stock, "setup fixture");
  const Box3 fixed = named(f, "vise fixed jaw").box, moving = named(f, "vise moving jaw").box;
  // The jaws touch the stock's y faces, stand 5 mm over its lowest face, and are centred along x.
  EXPECT_DOUBLE_EQ(fixed.max.y(), -2);
  EXPECT_DOUBLE_EQ(moving.min.y(), 42);
  EXPECT_DOUBLE_EQ(fixed.max.z(), 5);
  EXPECT_DOUBLE_EQ(fixed.max.x() - fixed.min.x(), 100);
  EXPECT_DOUBLE_EQ(0.5 * (fixed.max.x() + fixed.min.x()), 25);
  // The stock stands on 20 mm of parallels on the vise floor, 30 mm over the table.
  EXPECT_DOUBLE_EQ(f.seat, 50);
  EXPECT_DOUBLE_EQ(f.table_z, -50);
  EXPECT_DOUBLE_EQ(named(f, "parallel -y").box.max.z(), 0);
  EXPECT_NE(f.description.find("clamping the stock's y faces, 44 mm apart"), std::string::npos) << f.description;
  // Closing along x, the jaws meet the x faces.
  spec.vise.clamp = 'x';
  EXPECT_DOUBLE_EQ(named(place_fixture(spec, stock, "f"), "vise moving jaw").box.min.x(), 52);
}

TEST(Fixture, BadFixturesAreRefusedWithTheReason) {
  const Box3 stock = Box3::between(Vec3(0, 0, 0), Vec3(60, 60, 60));
  FixtureSpec spec;
  spec.kind = FixtureSpec::Kind::Vise;
  spec.vise.opening = 50;
  EXPECT_NE(error_of([&] { place_fixture(spec, stock, "setups[1].fixture"); })
                .find("setups[1].fixture.vise: the stock is 60 mm across the jaws (along y), the vise opens 50 mm"),
            std::string::npos);
  spec.vise = ViseSpec{};
  spec.vise.grip = 30;  // beyond the jaws' 25 mm
  EXPECT_NE(error_of([&] { place_fixture(spec, stock, "f"); }).find("f.vise.grip"), std::string::npos);
  spec.vise = ViseSpec{};
  spec.vise.clamp = 'z';
  EXPECT_NE(error_of([&] { place_fixture(spec, stock, "f"); }).find("must be x or y"), std::string::npos);
  spec = FixtureSpec{};
  spec.kind = FixtureSpec::Kind::Boxes;
  spec.boxes = {{"stop", Box3::between(Vec3(55, 0, 0), Vec3(70, 10, 10))}};
  EXPECT_NE(error_of([&] { place_fixture(spec, stock, "f"); }).find("box 'stop' cuts into the stock"),
            std::string::npos);
  spec.boxes = {{"stop", Box3::between(Vec3(60, 0, 0), Vec3(70, 10, 10))}};  // touching is holding
  EXPECT_EQ(place_fixture(spec, stock, "f").boxes.size(), 1u);
  spec = FixtureSpec{};
  spec.kind = FixtureSpec::Kind::Table;
  spec.clamps.count = 3;
  EXPECT_NE(error_of([&] { place_fixture(spec, stock, "f"); }).find("f.clamps.count: must be 2 or 4"),
            std::string::npos);
  spec.clamps.count = 4;
  const Fixture clamped = place_fixture(spec, stock, "f");
  EXPECT_EQ(clamped.boxes.size(), 4u);
  EXPECT_DOUBLE_EQ(named(clamped, "clamp +x").box.min.x(), 54);  // 6 mm onto the stock's top
  EXPECT_DOUBLE_EQ(named(clamped, "clamp +x").box.min.z(), 60);
}

// Which part of the tool enters: the cutter beside a jaw, the holder over it, nothing a hair away.
TEST(FixtureCollision, NamesThePartTheBoxAndTheMove) {
  Fixture f;
  f.boxes = {{"vise fixed jaw", Box3::between(Vec3(-50, -20, -25), Vec3(50, 0, 5))}};
  // The ball (r 3) plunging beside the jaw: 3.01 mm off its face is clear, 2.9 mm is in.
  EXPECT_FALSE(stock::first_fixture_collision(program({{Vec3(0, 3.01, 20), Vec3(0, 3.01, 0)}}), f));
  const auto cutter = stock::first_fixture_collision(program({{Vec3(0, 10, 20), Vec3(0, 10, 0)},
                                                              {Vec3(0, 10, 0), Vec3(0, 2.9, 0)}}),
                                                     f);
  ASSERT_TRUE(cutter);
  EXPECT_EQ(cutter->source, 2u);
  EXPECT_EQ(cutter->part, "cutter");
  EXPECT_EQ(cutter->box, "vise fixed jaw");
  // Deep beside the jaw (tip 30 mm under its top) the holder (r 14, 30 mm up) comes down onto it.
  const auto holder = stock::first_fixture_collision(program({{Vec3(0, 10, -20), Vec3(0, 10, -26)}}), f);
  ASSERT_TRUE(holder);
  EXPECT_EQ(holder->part, "holder");
  EXPECT_NE(holder->message().find("the holder enters the fixture's vise fixed jaw at move 1 (a feed from "
                                   "(0.000, 10.000, -20.000) to (0.000, 10.000, -26.000) mm)"),
            std::string::npos)
      << holder->message();
  // A rapid over the jaw's top at the cutter's clearance is no collision; 0.5 mm lower it is.
  EXPECT_FALSE(stock::first_fixture_collision(program({{Vec3(0, -30, 5.01), Vec3(0, 30, 5.01)}}, true), f));
  const auto rapid = stock::first_fixture_collision(program({{Vec3(0, -30, 4.5), Vec3(0, 30, 4.5)}}, true), f);
  ASSERT_TRUE(rapid);
  EXPECT_TRUE(rapid->rapid);
}

// The exact sweep against the tool's parts set down densely along random moves (a millionth of the move apart),
// each position a cylinder against the box: no position meets a box the sweep misses, and a sweep that meets
// one has a position within a hair of it.
TEST(FixtureCollision, SweepAgreesWithDensePositions) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-40, 40);
  const Box3 b = Box3::between(Vec3(-10, -5, -8), Vec3(12, 7, 3));
  const stock::ToolBody body = stock::tool_body(ball6());
  auto meets_at = [&](const Vec3& tip, const stock::ToolBodyPart& p, double grow) {
    const double zlo = tip.z() + p.from, zhi = tip.z() + p.to;
    if (!(zlo < b.max.z() + grow && zhi > b.min.z() - grow)) return false;
    const Vec2 gap = (b.min.head<2>() - tip.head<2>()).cwiseMax(tip.head<2>() - b.max.head<2>()).cwiseMax(Vec2::Zero());
    return gap.norm() < p.radius + grow;
  };
  int hits = 0;
  for (int k = 0; k < 400; ++k) {
    const Vec3 a(u(random), u(random), u(random)), c(u(random), u(random), u(random));
    for (const stock::ToolBodyPart& p : body) {
      const bool swept = stock::sweeps_into(a, c, p.radius, p.from, p.to, b);
      bool inside = false, near = false;
      const int n = 20000;
      for (int i = 0; i <= n; ++i) {
        const Vec3 tip = a + (c - a) * (double(i) / n);
        inside |= meets_at(tip, p, -0.01);
        near |= meets_at(tip, p, 0.01 + (c - a).norm() / n);
      }
      if (inside) {
        EXPECT_TRUE(swept) << p.name << " move " << k;
      }
      if (swept) {
        EXPECT_TRUE(near) << p.name << " move " << k;
      }
      hits += swept;
    }
  }
  EXPECT_GT(hits, 100);
}
