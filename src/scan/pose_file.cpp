#include "rosmill/scan/pose_file.hpp"

#include <vector>

#include <yaml-cpp/yaml.h>

#include "rosmill/error.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/input_file.hpp"
#include "rosmill/units.hpp"

namespace rosmill::core::scan {
namespace {

std::vector<double> numbers(const YAML::Node& node, size_t count, const std::string& where) {
  if (!node.IsSequence() || node.size() != count)
    throw Error(where, "must be a list of " + std::to_string(count) + " numbers");
  std::vector<double> out;
  for (const auto& item : node) {
    try {
      out.push_back(item.as<double>());
    } catch (const YAML::Exception&) {
      throw Error(where, "holds something that is not a number: '" + item.as<std::string>("?") + "'");
    }
  }
  return out;
}

}  // namespace

Eigen::Matrix4d parse_pose(const std::string& text, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error(name + ":" + std::to_string(e.mark.line + 1), "not YAML: " + e.msg);
  }
  if (!root.IsMap()) throw Error(name, "a pose file is a map with `matrix`, or `xyz` and `quaternion`");
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>("");
    if (key != "units" && key != "matrix" && key != "xyz" && key != "quaternion")
      throw Error(name, "unknown field '" + key + "' (known: units, matrix, xyz, quaternion)");
  }
  const double scale = root["units"] ? mm_per_unit(parse_units(root["units"].as<std::string>(""), name + " units"))
                                     : mm_per_unit(Units::Metre);
  const bool matrix = bool(root["matrix"]), split = root["xyz"] || root["quaternion"];
  if (matrix == split) throw Error(name, "give either `matrix` (16 numbers) or `xyz` and `quaternion`, not both");
  Eigen::Matrix4d t;
  if (matrix) {
    const std::vector<double> m = numbers(root["matrix"], 16, name + " matrix");
    for (int i = 0; i < 16; ++i) t(i / 4, i % 4) = m[size_t(i)];
    check_rigid(t, name + " matrix");
  } else {
    if (!root["xyz"] || !root["quaternion"]) throw Error(name, "`xyz` and `quaternion` go together");
    const std::vector<double> x = numbers(root["xyz"], 3, name + " xyz");
    const std::vector<double> q = numbers(root["quaternion"], 4, name + " quaternion");
    t = rigid_from_xyz_quat(Vec3(x[0], x[1], x[2]), Eigen::Vector4d(q[0], q[1], q[2], q[3]), name);
  }
  t.topRightCorner<3, 1>() *= scale;
  return t;
}

Eigen::Matrix4d read_pose_file(const std::string& path) {
  return parse_pose(read_input_file(path, 1 << 20), path);
}

}  // namespace rosmill::core::scan
