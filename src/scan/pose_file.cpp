#include "rosmill/scan/pose_file.hpp"

#include <vector>

#include <yaml-cpp/yaml.h>

#include "rosmill/error.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/input_file.hpp"
#include "rosmill/units.hpp"
#include "rosmill/yaml/fields.hpp"

namespace rosmill::core::scan {
namespace {

std::vector<double> numbers(const yaml::Fields& f, const std::string& key, size_t count) {
  const YAML::Node node = f.node(key);
  if (!node.IsSequence() || node.size() != count)
    f.fail(key, "must be a list of " + std::to_string(count) + " numbers");
  std::vector<double> out;
  for (const auto& item : node) out.push_back(f.converted<double>(item, key, "holds something that is not a number"));
  return out;
}

}  // namespace

Eigen::Matrix4d parse_pose(const std::string& text, const std::string& name) {
  const YAML::Node root = yaml::parse(text, name);
  if (!root.IsMap())
    throw Error(yaml::line_of(root, name), "a pose file is a map with `matrix`, or `xyz` and `quaternion`");
  const yaml::Fields f(root, name, "", {"units", "matrix", "xyz", "quaternion"});
  const double scale =
      f.has("units") ? mm_per_unit(parse_units(f.text("units", ""), f.where("units"))) : mm_per_unit(Units::Metre);
  const bool matrix = f.has("matrix"), split = f.has("xyz") || f.has("quaternion");
  if (matrix == split)
    throw Error(yaml::line_of(root, name), "give either `matrix` (16 numbers) or `xyz` and `quaternion`, not both");
  Eigen::Matrix4d t;
  if (matrix) {
    const std::vector<double> m = numbers(f, "matrix", 16);
    for (int i = 0; i < 16; ++i) t(i / 4, i % 4) = m[size_t(i)];
    check_rigid(t, f.where("matrix"));
  } else {
    if (!f.has("xyz") || !f.has("quaternion"))
      f.fail(f.has("xyz") ? "quaternion" : "xyz", "`xyz` and `quaternion` go together");
    const std::vector<double> x = numbers(f, "xyz", 3);
    const std::vector<double> q = numbers(f, "quaternion", 4);
    t = rigid_from_xyz_quat(Vec3(x[0], x[1], x[2]), Eigen::Vector4d(q[0], q[1], q[2], q[3]), f.where("quaternion"));
  }
  t.topRightCorner<3, 1>() *= scale;
  return t;
}

Eigen::Matrix4d read_pose_file(const std::string& path) {
  return parse_pose(read_input_file(path, 1 << 20), path);
}

}  // namespace rosmill::core::scan
