// A setup filter (Lefebvre & Lauwers, section 3.3, fig. 9): the tool directions a workpiece setup allows, and so which
// facet
// normals it reaches. A facet is reachable when its outward normal makes at most `max_angle_deg` (90 by
// default) with some allowed tool axis: with 90 degrees a vertical wall is reached by the cutter's side, an
// undercut is not.
//   3-axis along +X, -X, +Y, -Y, +Z or -Z: the one tool axis.
//   4-axis about an axis u: the tool axis turns in the plane perpendicular to u.
//   5-axis: every direction.
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::segment {

struct SetupFilter {
  enum class Kind { ThreeAxis, FourAxis, FiveAxis };
  Kind kind = Kind::ThreeAxis;
  Vec3 axis = Vec3::UnitZ();  // tool axis (3-axis) or rotary axis (4-axis), unit length
  double max_angle_deg = 90.0;
  std::string name = "+z";

  // True when a facet with this unit outward normal is reachable (a zero normal is: it has no area).
  bool reaches(const Vec3& normal) const;
  // Angle (radians) from a unit direction to the nearest allowed tool axis.
  double angle_to_allowed(const Vec3& direction) const;
};

// SetupFilter::reaches with its bound worked out once (a cosine or a sine), for loops over every facet.
class ReachTest {
 public:
  explicit ReachTest(const SetupFilter& filter);
  bool operator()(const Vec3& normal) const {
    switch (kind_) {
      case SetupFilter::Kind::ThreeAxis: return normal.dot(axis_) >= bound_;
      case SetupFilter::Kind::FourAxis: return std::abs(normal.dot(axis_)) <= bound_;
      case SetupFilter::Kind::FiveAxis: return true;
    }
    return true;
  }

 private:
  SetupFilter::Kind kind_;
  Vec3 axis_;
  double bound_;
};

// "+z", "-x", ... (3-axis), "4axis:x" (also y, z), "5axis". Throws Error naming the text otherwise.
SetupFilter parse_setup(const std::string& text);
// A comma-separated list of the above.
std::vector<SetupFilter> parse_setups(const std::string& list);
// The six 3-axis setups in the order +z, -z, +x, -x, +y, -y.
const std::vector<SetupFilter>& axis_setups();

// The filter of a setup: named ("+Z", "z", "-x", "4axis:x", "5axis", any case) or, when name is empty, the 3-axis
// setup of `direction`. Its name is "+Z"-style for 3-axis setups. Throws Error naming `where`.
SetupFilter setup_filter_of(const std::string& name, const Vec3& direction, double max_angle_deg,
                            const std::string& where = "setup");

}  // namespace rosmill::core::segment
