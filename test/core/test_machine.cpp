// Kinds of machine (machine/machine.hpp): each one's joints from its machine file, forward and inverse kinematics
// that agree (the branch nearest the joints before kept), and the setups it can turn the part to.
#include <gtest/gtest.h>

#include <random>

#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/machine/machine.hpp"

using namespace rosmill::core;

namespace {

const std::string kConfig = std::string(ROSMILL_SOURCE_DIR) + "/config/";

}  // namespace

TEST(Machine, ThreeAxisMillFromItsFile) {
  const gcode::MachineLimits limits = gcode::load_machine_limits(kConfig + "machine.yaml");
  const auto m = limits.machine();
  EXPECT_EQ(m->kind(), "3-axis mill");
  EXPECT_FALSE(m->turns_part());
  EXPECT_FALSE(m->simultaneous());
  EXPECT_EQ(m->trunnion(), nullptr);
  ASSERT_EQ(m->joints().size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(m->joints()[size_t(i)].min, limits.envelope.min[i]);
    EXPECT_EQ(m->joints()[size_t(i)].max, limits.envelope.max[i]);
  }
  const Vec3 p = 0.5 * (limits.envelope.min + limits.envelope.max);
  const auto q = m->inverse({p, Vec3::UnitZ()}, m->home());
  ASSERT_TRUE(q);
  EXPECT_LT((m->forward(*q).tip - p).norm(), 1e-12);
  std::string why;
  EXPECT_FALSE(m->inverse({p, Vec3(1, 0, 1).normalized()}, m->home(), &why));
  EXPECT_NE(why.find("along +Z"), std::string::npos) << why;
  EXPECT_FALSE(m->inverse({p, Vec3::Constant(NAN)}, m->home()));  // no axis at all
  EXPECT_FALSE(m->inverse({Vec3::Constant(NAN), Vec3::UnitZ()}, m->home()));
  EXPECT_FALSE(m->inverse({limits.envelope.max + Vec3(0, 0, 1), Vec3::UnitZ()}, m->home(), &why));
  EXPECT_EQ(why.rfind("Z ", 0), 0u) << why;
  // Every side is a setup on a mill: the part is turned over by hand, the joints stay where they are.
  const auto s = m->setup_joints(-Vec3::UnitZ(), *q);
  ASSERT_TRUE(s);
  EXPECT_EQ(*s, *q);
}

TEST(Machine, TrunnionForwardAndInverseAgreeOnItsBranch) {
  const gcode::MachineLimits limits = gcode::load_machine_limits(kConfig + "machine_xyzac.yaml");
  const auto m = limits.machine();
  EXPECT_EQ(m->kind(), "trunnion (3+2)");
  EXPECT_TRUE(m->turns_part());
  EXPECT_FALSE(m->simultaneous());
  ASSERT_NE(m->trunnion(), nullptr);
  ASSERT_EQ(m->joints().size(), 5u);
  EXPECT_EQ(m->joint("A")->min, limits.trunnion->a.min);
  EXPECT_EQ(m->joint("C")->max, limits.trunnion->c.max);
  EXPECT_TRUE(m->joint("A")->rotary);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0, 1);
  size_t checked = 0;
  for (int n = 0; n < 500; ++n) {
    machine::JointValues q(5);
    for (size_t k = 0; k < 5; ++k) {
      const machine::Joint& j = m->joints()[k];
      q[k] = j.min + (j.max - j.min) * u(rng);
    }
    if (std::abs(q[3]) < 1e-3) continue;  // on the pole any C is a solution
    const machine::ToolPose pose = m->forward(q);
    EXPECT_NEAR(pose.axis.norm(), 1.0, 1e-12);
    // From the joints themselves the inverse gives them back: the branch and C's turn nearest are theirs.
    const auto back = m->inverse(pose, q);
    ASSERT_TRUE(back) << n;
    for (size_t k = 0; k < 5; ++k) EXPECT_NEAR((*back)[k], q[k], 1e-7) << n << " joint " << k;
    // From elsewhere it may take the other branch, but the tool is where it was.
    const auto other = m->inverse(pose, m->home());
    if (!other) continue;
    const machine::ToolPose again = m->forward(*other);
    EXPECT_LT((again.tip - pose.tip).norm(), 1e-9) << n;
    EXPECT_LT((again.axis - pose.axis).norm(), 1e-12) << n;
    ++checked;
  }
  EXPECT_GT(checked, 100u);
}

TEST(Machine, TrunnionRefusesSetupsItsRangesCannotReach) {
  const auto m = gcode::load_machine_limits(kConfig + "machine_xyzac.yaml").machine();
  std::string why;
  // A in [-100, 50]: the part's underside (A = 180) is out of reach; its side (A = +-90) is not.
  EXPECT_FALSE(m->setup_joints(-Vec3::UnitZ(), m->home(), &why));
  EXPECT_NE(why.find("A's range"), std::string::npos) << why;
  const auto side = m->setup_joints(Vec3::UnitX(), m->home());
  ASSERT_TRUE(side);
  EXPECT_LT((m->forward(*side).axis - Vec3::UnitX()).norm(), 1e-12);
  EXPECT_FALSE(m->inverse({Vec3::Constant(NAN), Vec3::UnitX()}, m->home()));  // no tip
  EXPECT_FALSE(m->inverse({Vec3::Zero(), Vec3::Constant(NAN)}, m->home()));   // no axis
}

TEST(Machine, TrunnionWithToolCentrePointControlCutsSimultaneously) {
  const auto m = gcode::load_machine_limits(kConfig + "machine_xyzac_tcp.yaml").machine();
  EXPECT_EQ(m->kind(), "trunnion with tool-centre-point control");
  EXPECT_TRUE(m->turns_part());
  EXPECT_TRUE(m->simultaneous());
}
