#include "rosmill/segment/setup_frame.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::core {

void check_setup(const SetupFrame& s, const std::string& where) {
  const std::string name = where + (s.name.empty() ? "" : " " + s.name);
  if (!s.tool_axis.allFinite() || std::abs(s.tool_axis.norm() - 1) > 1e-6)
    throw Error(name, "the tool axis must be a finite unit vector");
  if (!s.to_setup.coeffs().allFinite() || std::abs(s.to_setup.norm() - 1) > 1e-6)
    throw Error(name, "the rotation must be a finite unit quaternion");
  if ((s.to_setup * s.tool_axis - Vec3::UnitZ()).norm() > 1e-6)
    throw Error(name, "the rotation does not turn the tool axis onto +Z");
}

SetupFrame direction_setup(const Vec3& direction, const std::string& where) {
  if (!direction.allFinite() || direction.norm() < 1e-9)
    throw Error(where, "the tool direction must be a finite non-zero vector");
  SetupFrame s;
  s.name = "custom";
  s.tool_axis = direction.normalized();
  // The shortest rotation taking the tool axis onto +Z: a part fixtured for that setup, seen by the machine.
  s.to_setup = Eigen::Quaterniond::FromTwoVectors(s.tool_axis, Vec3::UnitZ());
  return s;
}

SetupFrame named_setup(const std::string& name, const std::string& where) {
  std::string n = name;
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return std::toupper(c); });
  if (n.size() == 1) n = "+" + n;
  Vec3 axis;
  if (n.size() != 2 || (n[0] != '+' && n[0] != '-'))
    throw Error(where, "unknown setup '" + name + "' (expected +Z, -Z, +X, -X, +Y or -Y, or a direction)");
  const double sign = n[0] == '+' ? 1.0 : -1.0;
  switch (n[1]) {
    case 'X': axis = sign * Vec3::UnitX(); break;
    case 'Y': axis = sign * Vec3::UnitY(); break;
    case 'Z': axis = sign * Vec3::UnitZ(); break;
    default: throw Error(where, "unknown setup '" + name + "' (expected +Z, -Z, +X, -X, +Y or -Y, or a direction)");
  }
  SetupFrame s = direction_setup(axis, where);
  if (n == "-Z") s.to_setup = Eigen::AngleAxisd(M_PI, Vec3::UnitX());  // a defined flip, not an arbitrary axis
  s.name = n;
  return s;
}

SetupFrame resolve_setup(const std::string& name, const Vec3& direction) {
  return name.empty() ? direction_setup(direction) : named_setup(name);
}

segment::SetupFilter setup_filter_of(const std::string& name, const Vec3& direction, double max_angle_deg,
                                     const std::string& where) {
  if (!std::isfinite(max_angle_deg) || max_angle_deg <= 0 || max_angle_deg > 180)
    throw Error(where, "max angle must lie in (0, 180] degrees, got " + std::to_string(max_angle_deg));
  segment::SetupFilter filter;
  if (name.empty()) {
    filter.axis = direction_setup(direction, where).tool_axis;
    filter.name = "custom";
  } else {
    std::string text = name;
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
    if (text.size() == 1) text = "+" + text;
    try {
      filter = segment::parse_setup(text);
    } catch (const Error&) {
      throw Error(where, "unknown setup '" + name + "' (expected +Z, -Z, +X, -X, +Y, -Y, 4axis:x|y|z or 5axis)");
    }
    if (filter.kind == segment::SetupFilter::Kind::ThreeAxis) filter.name = named_setup(text, where).name;
  }
  filter.max_angle_deg = max_angle_deg;
  return filter;
}

Mesh mesh_in_setup(const Mesh& mesh, const SetupFrame& setup) {
  if (setup.identity()) return mesh;
  std::vector<Vec3> corners;
  corners.reserve(mesh.faces.size() * 3);
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int i = 0; i < 3; ++i) corners.push_back(setup.to_setup_frame(mesh.corner(f, i)));
  return build_mesh(corners);
}

PointCloud cloud_in_setup(const PointCloud& cloud, const SetupFrame& setup) {
  if (setup.identity()) return cloud;
  PointCloud out;
  out.points.reserve(cloud.points.size());
  const Eigen::Matrix3d r = setup.to_setup.toRotationMatrix();
  for (const Vec3& p : cloud.points) out.points.push_back(r * p);
  out.recompute_bbox();
  return out;
}

}  // namespace rosmill::core
