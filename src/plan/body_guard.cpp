#include "body_guard.hpp"

#include "rosmill/plan/tool_body_surface.hpp"

namespace rosmill::core {

void BodyGuard::at_level(const MaterialTop& left, const Tool& tool, double allowance, double z) {
  bodies_.clear();
  z_ = z;
  const double top = left.highest();
  const Cutter& c = tool.cutter;
  const double radius[2] = {0.5 * c.shank_diameter, 0.5 * tool.holder_mm()};
  const double height[2] = {c.flute_length, tool.stick_out_mm()};
  for (int b = 0; b < 2; ++b)
    if (radius[b] > c.radius() && top > z + height[b])
      bodies_.emplace_back(left.highest_within(radius[b] + allowance + kBodyClearance), height[b]);
}

}  // namespace rosmill::core
