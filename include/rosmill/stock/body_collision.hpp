// The tool's body above the cutter against the material the stock still holds: the shank (from the flute length up,
// where it is wider than the cutter) and the holder (from the stick-out up), each a flat-ended cylinder. A program
// whose shank or holder would run into material is a crash, however the cutter below it cuts: found as the removal
// simulation would find those cylinders cutting, on the stock's view from the program's setup, without removing
// anything.
#pragma once
#include <optional>
#include <string>

#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/stock/in_process_stock.hpp"

namespace rosmill::core::stock {

struct BodyCollision {
  size_t move = 0;          // index into the program's moves
  uint32_t source = 0;      // its G-code line or toolpath move number
  std::string body;         // "shank" or "holder"
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // the move's tip, setup frame (mm)
  // "the holder runs into the stock at move 1234 (a feed from (x, y, z) to (x, y, z) mm)"
  std::string message() const;
};

// The first move of `program` (in the frame of `setup`) whose shank or holder meets the stock's material; none when
// the stock stands nowhere higher over the tip than those bodies begin.
std::optional<BodyCollision> first_body_collision(const MachineProgram& program, const InProcessStock& stock,
                                                  const SetupFrame& setup);

}  // namespace rosmill::core::stock
