#include "rosmill/gcode/work_offset.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "rosmill/error.hpp"
#include "rosmill/gcode/number_format.hpp"
#include "rosmill/geometry/rigid_transform.hpp"

namespace rosmill::core::gcode {
namespace {

constexpr double kDegree = M_PI / 180.0;
// A turn below this is below every controller's angular resolution over the envelope (1e-4 degrees moves a point
// 0.5 m away by under a micrometre): a dialect without R may write none.
constexpr double kNegligibleTurnDeg = 1e-4;

Eigen::Matrix3d turn_about_z(double degrees) {
  return Eigen::AngleAxisd(degrees * kDegree, Vec3::UnitZ()).toRotationMatrix();
}

}  // namespace

std::string WorkOffset::code() const { return "G5" + std::to_string(3 + index); }

Vec3 WorkOffset::to_machine(const Vec3& program) const { return origin + turn_about_z(rotation_deg) * program; }

Vec3 WorkOffset::to_program(const Vec3& machine) const {
  return turn_about_z(rotation_deg).transpose() * (machine - origin);
}

Eigen::Matrix4d WorkOffset::pose() const {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.topLeftCorner<3, 3>() = turn_about_z(rotation_deg);
  t.topRightCorner<3, 1>() = origin;
  return t;
}

WorkOffset work_offset_of_pose(const Eigen::Matrix4d& pose, double max_tilt_deg, const std::string& where) {
  check_rigid(pose, where);
  if (!(max_tilt_deg >= 0 && max_tilt_deg < 90))
    throw Error(where, "the largest tilt must be in [0, 90) degrees, got " + std::to_string(max_tilt_deg));
  const Eigen::Matrix3d r = pose.topLeftCorner<3, 3>();
  const double tilt = std::acos(std::clamp(r(2, 2), -1.0, 1.0)) / kDegree;
  if (tilt > max_tilt_deg) {
    std::ostringstream s;
    s.precision(4);
    s << "the workpiece is tilted " << tilt << " degrees out of the table's plane (at most " << max_tilt_deg
      << " allowed): a work offset turns the program about Z only, so a 3-axis program would cut the tilted part "
         "wrongly; re-clamp the part level or plan on the registered pose (rosmill plan --place)";
    throw Error(where, s.str());
  }
  WorkOffset w;
  w.origin = pose.topRightCorner<3, 1>();
  // The turn about Z that takes the machine's X axis to the workpiece's X axis seen from above.
  w.rotation_deg = std::atan2(r(1, 0), r(0, 0)) / kDegree;
  return w;
}

std::string work_offset_block(const WorkOffset& w, const Dialect& d, int decimals) {
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(w.origin[a])) throw Error("work offset", "origin is not a finite number");
  if (!std::isfinite(w.rotation_deg)) throw Error("work offset", "rotation is not a finite number");
  if (w.index < 1 || w.index > kWorkOffsets)
    throw Error("work offset", "P" + std::to_string(w.index) + " is not one of P1..P6 (G54..G59)");
  std::string b = "G10 L2 P" + std::to_string(w.index);
  static const char axis[3] = {'X', 'Y', 'Z'};
  for (int a = 0; a < 3; ++a) {
    b.push_back(' ');
    append_word(b, axis[a], w.origin[a], decimals);
  }
  if (d.coordinate_rotation) {
    b.push_back(' ');
    append_word(b, 'R', w.rotation_deg, 4);
  } else if (std::abs(w.rotation_deg) > kNegligibleTurnDeg) {
    std::ostringstream s;
    s.precision(4);
    s << d.name << " has no coordinate system rotation (G10 L2 R) and the part is turned " << w.rotation_deg
      << " degrees on the table: turn it square to the machine's axes (within " << kNegligibleTurnDeg
      << " degrees) or use a controller that rotates its work offsets";
    throw Error("work offset", s.str());
  }
  return b;
}

WorkOffset parse_work_offset(const std::string& text, const std::string& where) {
  std::vector<double> v;
  if (!text.empty() && text.back() == ',') throw Error(where, "ends with a comma: expected x,y,z[,rotation_deg]");
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    size_t used = 0;
    double x = NAN;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    while (used < item.size() && std::isspace(static_cast<unsigned char>(item[used]))) ++used;
    if (used == 0 || used != item.size() || !std::isfinite(x))
      throw Error(where, "'" + item + "' is not a number (expected x,y,z[,rotation_deg] in mm and degrees)");
    v.push_back(x);
  }
  if (v.size() != 3 && v.size() != 4)
    throw Error(where, "expected x,y,z[,rotation_deg] (mm, degrees), got " + std::to_string(v.size()) + " numbers");
  WorkOffset w;
  w.origin = Vec3(v[0], v[1], v[2]);
  if (v.size() == 4) w.rotation_deg = v[3];
  return w;
}

}  // namespace rosmill::core::gcode
