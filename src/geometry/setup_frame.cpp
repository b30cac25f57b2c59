#include "rosmill/geometry/setup_frame.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::core {
namespace {

Placement turn(const std::string& name, const Eigen::Quaterniond& rotation) {
  return placement_of("setup " + name, kWorkpieceFrame, rotation);
}

}  // namespace

SetupFrame SetupFrame::with_origin(const Vec3& origin) const {
  SetupFrame s = *this;
  s.placement.pose.pretranslate(-origin);
  return s;
}

bool SetupFrame::same_as(const SetupFrame& other) const {
  return (placement.pose.matrix() - other.placement.pose.matrix()).cwiseAbs().maxCoeff() < 1e-9;
}

void check_setup(const SetupFrame& s, const std::string& where) {
  const std::string name = where + (s.name.empty() ? "" : " " + s.name);
  if (!s.tool_axis.allFinite() || std::abs(s.tool_axis.norm() - 1) > 1e-6)
    throw Error(name, "the tool axis must be a finite unit vector");
  check_placement(s.placement, name);
  if ((s.direction_to_setup(s.tool_axis) - Vec3::UnitZ()).norm() > 1e-6)
    throw Error(name, "the placement does not turn the tool axis onto +Z");
}

std::string setup_name_of(const Vec3& d) {
  static const char* names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  for (int a = 0; a < 3; ++a)
    for (int s = 0; s < 2; ++s)
      if ((d - (s ? -1.0 : 1.0) * Vec3::Unit(a)).norm() < 1e-9) return names[2 * a + s];
  return "custom";
}

SetupFrame direction_setup(const Vec3& direction, const std::string& where) {
  if (!direction.allFinite() || direction.norm() < 1e-9)
    throw Error(where, "the tool direction must be a finite non-zero vector");
  SetupFrame s;
  s.tool_axis = direction.normalized();
  s.name = setup_name_of(s.tool_axis);
  // The shortest rotation taking the tool axis onto +Z: a part fixtured for that setup, seen by the machine. -Z
  // turns about X, a defined flip rather than the arbitrary axis a half turn would take.
  const Eigen::Quaterniond r = s.name == "-Z" ? Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Vec3::UnitX()))
                                              : Eigen::Quaterniond::FromTwoVectors(s.tool_axis, Vec3::UnitZ());
  s.placement = turn(s.name == "custom" ? "custom" : s.name, r);
  return s;
}

SetupFrame named_setup(const std::string& name, const std::string& where) {
  std::string n = name;
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return std::toupper(c); });
  if (n.size() == 1) n = "+" + n;
  const std::string expected = "unknown setup '" + name + "' (expected +Z, -Z, +X, -X, +Y or -Y, or a direction)";
  if (n.size() != 2 || (n[0] != '+' && n[0] != '-')) throw Error(where, expected);
  const double sign = n[0] == '+' ? 1.0 : -1.0;
  switch (n[1]) {
    case 'X': return direction_setup(sign * Vec3::UnitX(), where);
    case 'Y': return direction_setup(sign * Vec3::UnitY(), where);
    case 'Z': return direction_setup(sign * Vec3::UnitZ(), where);
    default: throw Error(where, expected);
  }
}

SetupFrame resolve_setup(const std::string& name, const Vec3& direction) {
  return name.empty() ? direction_setup(direction) : named_setup(name);
}

}  // namespace rosmill::core
