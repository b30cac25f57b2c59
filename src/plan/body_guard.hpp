// The tool's shank (where wider than its cutter) and holder over the material the levels so far left. The part
// itself the tool's body surface keeps them off (tool_body_surface.hpp); the material is what the levels above could
// not clear (beside the part's walls, the fixture, a corner), which a body comes down onto at a level a stick-out
// below. A z-level strategy asks at each level where its cutter may not go for the bodies above it.
#pragma once
#include <utility>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/types.hpp"
#include "rosmill/plan/material_top.hpp"

namespace rosmill::core {

class BodyGuard {
 public:
  // The bodies that may meet `left` with the tip at z: each a map of the highest material within its reach (its
  // radius, the allowance and the bodies' clearance) and its height above the tip. None where the material stands
  // no higher than a body's height over z.
  void at_level(const MaterialTop& left, const Tool& tool, double allowance, double z);
  // Whether a body meets the material with the tip at p, at the level's z.
  bool blocked(const Vec2& p) const {
    for (const auto& [near, height] : bodies_)
      if (near.top_at(p) > z_ + height) return true;
    return false;
  }
  bool any() const { return !bodies_.empty(); }

 private:
  std::vector<std::pair<MaterialTop, double>> bodies_;
  double z_ = 0.0;
};

}  // namespace rosmill::core
