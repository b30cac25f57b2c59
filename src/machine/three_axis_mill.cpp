#include "rosmill/machine/machine.hpp"

namespace rosmill::core::machine {
namespace {
// Three linear joints; the tool tip is where they are, the tool along +Z. Each setup is a clamping of its own.
class ThreeAxisMill final : public Machine {
 public:
  ThreeAxisMill(const Box3& travel, const Vec3& velocity, const Vec3& acceleration)
      : joints_(linear_joints(travel, velocity, acceleration)) {}
  std::string kind() const override { return "3-axis mill"; }
  const std::vector<Joint>& joints() const override { return joints_; }
  ToolPose forward(const JointValues& q) const override { return {Vec3(q.at(0), q.at(1), q.at(2)), Vec3::UnitZ()}; }
  std::optional<JointValues> inverse(const ToolPose& pose, const JointValues&, std::string* why) const override {
    if (!((pose.axis.normalized() - Vec3::UnitZ()).norm() <= 1e-9)) {  // a NaN axis too
      if (why) *why = "a 3-axis mill holds the tool along +Z";
      return std::nullopt;
    }
    const JointValues q{pose.tip.x(), pose.tip.y(), pose.tip.z()};
    if (!within_limits(q, why)) return std::nullopt;
    return q;
  }
  bool turns_part() const override { return false; }
  bool simultaneous() const override { return false; }
  std::optional<JointValues> setup_joints(const Vec3&, const JointValues& near, std::string*) const override {
    return near;  // the part is turned over in its fixture by hand
  }

 private:
  std::vector<Joint> joints_;
};

}  // namespace

std::shared_ptr<const Machine> three_axis_mill(const Box3& travel, const Vec3& velocity, const Vec3& acceleration) {
  return std::make_shared<ThreeAxisMill>(travel, velocity, acceleration);
}

}  // namespace rosmill::core::machine
