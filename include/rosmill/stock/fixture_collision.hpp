// The fixture in the stock's collision world: no move of a program, feed or rapid, may take the tool, its shank or
// its holder into a box of the fixture that holds the part. The tool is three coaxial cylinders above its tip: the
// cutter (its diameter, up to the flute length; a ball's or a bull nose's corner is inside that cylinder, so the
// check errs on the safe side there), the shank (up to the stick-out) and the holder (its diameter, from the
// stick-out up without end). A straight move sweeps each exactly: it meets a box when, over the part of the move
// where the cylinder's height range overlaps the box's, the tool axis comes nearer the box's XY rectangle than the
// cylinder's radius. An arc is checked as the straight moves of its bounding box's sides would (more than it sweeps).
// Touching is not entering: a cylinder must go more than kFixtureClearance into a box to collide.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "rosmill/fixture/fixture.hpp"
#include "rosmill/stock/program.hpp"

namespace rosmill::core::stock {

constexpr double kFixtureClearance = 1e-4;  // mm

struct ToolBodyPart {
  const char* name;    // "cutter", "shank", "holder"
  double radius;       // mm
  double from, to;     // mm above the tip (to: +infinity for the holder)
};
using ToolBody = std::array<ToolBodyPart, 3>;

ToolBody tool_body(const Tool& tool);

struct FixtureCollision {
  size_t move = 0;        // index into the program's moves
  uint32_t source = 0;    // its G-code line or toolpath move number
  bool rapid = false;
  std::string part;       // "cutter", "shank" or "holder"
  std::string box;        // the fixture box's name
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // the move's tip, setup frame (mm)
  // "the holder enters the fixture's vise fixed jaw at move 1234 (a feed from (x, y, z) to (x, y, z) mm)"
  std::string message() const;
};

// The first move whose tool meets a box of the fixture (the program and the fixture in the same setup frame).
std::optional<FixtureCollision> first_fixture_collision(const MachineProgram& program,
                                                        const fixture::Fixture& fixture);

// Whether a cylinder of `radius` over heights [from, to] above a tip moving from a to b goes into `box`.
bool sweeps_into(const Vec3& a, const Vec3& b, double radius, double from, double to, const Box3& box);

}  // namespace rosmill::core::stock
