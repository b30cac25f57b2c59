#include "rosmill/machine/machine.hpp"

#include <algorithm>

#include "rosmill/number_text.hpp"

namespace rosmill::core::machine {

const Joint* Machine::joint(const std::string& name) const {
  for (const Joint& j : joints())
    if (j.name == name) return &j;
  return nullptr;
}

JointValues Machine::home() const {
  JointValues q;
  for (const Joint& j : joints()) q.push_back(std::clamp(0.0, j.min, j.max));
  return q;
}

std::vector<Joint> linear_joints(const Box3& travel, const Vec3& velocity, const Vec3& acceleration) {
  std::vector<Joint> js;
  for (int i = 0; i < 3; ++i)
    js.push_back({std::string(1, char('X' + i)), false, travel.min[i], travel.max[i], velocity[i], acceleration[i]});
  return js;
}

bool Machine::within_limits(const JointValues& q, std::string* why) const {
  const std::vector<Joint>& js = joints();
  for (size_t k = 0; k < js.size() && k < q.size(); ++k) {
    if (js[k].within(q[k])) continue;
    const int digits = js[k].rotary ? 4 : 3;
    if (why)
      *why = js[k].name + " " + decimal_text(q[k], digits) + (js[k].rotary ? " degrees" : " mm") +
             " outside its range [" + decimal_text(js[k].min, digits) + ", " + decimal_text(js[k].max, digits) + "]";
    return false;
  }
  return true;
}

}  // namespace rosmill::core::machine
