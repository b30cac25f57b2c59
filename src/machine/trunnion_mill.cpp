#include "rosmill/machine/machine.hpp"

namespace rosmill::core::machine {
namespace {
// X Y Z A C. The linear joints are the machine's coordinates of the tool tip, A and C turn the table under it
// (machine/trunnion.hpp): the tip's workpiece point is the table point under the machine point.
class TrunnionMill final : public Machine {
 public:
  TrunnionMill(const Trunnion& t, const Box3& travel, const Vec3& velocity, const Vec3& acceleration)
      : t_(t), joints_(linear_joints(travel, velocity, acceleration)) {
    joints_.push_back({"A", true, t.a.min, t.a.max, t.a.velocity, t.a.acceleration});
    joints_.push_back({"C", true, t.c.min, t.c.max, t.c.velocity, t.c.acceleration});
  }
  std::string kind() const override {
    return t_.mode == KinematicsMode::ToolCentrePoint ? "trunnion with tool-centre-point control" : "trunnion (3+2)";
  }
  const std::vector<Joint>& joints() const override { return joints_; }
  ToolPose forward(const JointValues& q) const override {
    const Index i = index_of(q);
    return {t_.table_point(Vec3(q.at(0), q.at(1), q.at(2)), i.a, i.c), t_.tool_axis(i.a, i.c)};
  }
  std::optional<JointValues> inverse(const ToolPose& pose, const JointValues& near, std::string* why) const override {
    std::optional<JointValues> q = setup_joints(pose.axis, near, why);
    if (!q) return std::nullopt;
    const Index i = index_of(*q);
    const Vec3 m = t_.machine_point(pose.tip, i.a, i.c);
    for (int k = 0; k < 3; ++k) (*q)[size_t(k)] = m[k];
    if (!within_limits(*q, why)) return std::nullopt;
    return q;
  }
  bool turns_part() const override { return true; }
  bool simultaneous() const override { return t_.mode == KinematicsMode::ToolCentrePoint; }
  std::optional<JointValues> setup_joints(const Vec3& direction, const JointValues& near,
                                          std::string* why) const override {
    const std::optional<Index> i = index_for(t_, direction, index_of(near), why);
    if (!i) return std::nullopt;
    JointValues q = near;
    q[3] = i->a;
    q[4] = i->c;
    return q;
  }
  const Trunnion* trunnion() const override { return &t_; }

 private:
  Trunnion t_;
  std::vector<Joint> joints_;
};

}  // namespace

std::shared_ptr<const Machine> trunnion_mill(const Trunnion& trunnion, const Box3& travel, const Vec3& velocity,
                                             const Vec3& acceleration) {
  return std::make_shared<TrunnionMill>(trunnion, travel, velocity, acceleration);
}

}  // namespace rosmill::core::machine
