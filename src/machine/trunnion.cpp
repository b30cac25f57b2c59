#include "rosmill/machine/trunnion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "rosmill/number_text.hpp"

namespace rosmill::core::machine {
namespace {

constexpr double kDegree = M_PI / 180.0;

Eigen::Matrix3d turn(double a, double c) {
  return (Eigen::AngleAxisd(a * kDegree, Vec3::UnitX()) * Eigen::AngleAxisd(c * kDegree, Vec3::UnitZ()))
      .toRotationMatrix();
}

Vec3 pivot_of(const Trunnion& t) { return Vec3(0, t.pivot.y(), t.pivot.z()); }

// The turn of C by whole turns nearest `near` (the axis can go round many times; the least motion wins).
double nearest_turn(double c, double near) { return c + 360.0 * std::round((near - c) / 360.0); }

std::string degrees(double v) { return significant_text(v, 4); }

}  // namespace

Vec3 Trunnion::machine_point(const Vec3& p, double a, double c) const {
  const Eigen::AngleAxisd ra(a * kDegree, Vec3::UnitX()), rc(c * kDegree, Vec3::UnitZ());
  const Vec3 pv = pivot_of(*this);
  return ra * (rc * (p - centre) - pv) + pv + centre;
}

Vec3 Trunnion::table_point(const Vec3& m, double a, double c) const {
  const Eigen::AngleAxisd ra(-a * kDegree, Vec3::UnitX()), rc(-c * kDegree, Vec3::UnitZ());
  const Vec3 pv = pivot_of(*this);
  return rc * (ra * (m - pv - centre) + pv) + centre;
}

Vec3 Trunnion::tool_axis(double a, double c) const { return turn(a, c).transpose() * Vec3::UnitZ(); }

Placement Trunnion::table_in_machine(double a, double c) const {
  Placement p{"machine", "table", Eigen::Isometry3d::Identity()};
  p.pose.linear() = turn(a, c);
  p.pose.translation() = machine_point(Vec3::Zero(), a, c);
  return p;
}

std::optional<Index> index_for(const Trunnion& t, const Vec3& direction, const Index& from, std::string* why) {
  const Vec3 d = direction.normalized();
  const double a0 = std::acos(std::clamp(d.z(), -1.0, 1.0)) / kDegree;
  std::vector<Index> candidates;
  if (d.head<2>().norm() < 1e-12) {
    // Along the table's axis: A alone (0 or 180), C where it is.
    candidates.push_back({a0, from.c});
  } else {
    const double phi = std::atan2(d.y(), d.x()) / kDegree;
    for (const double a : {a0, -a0}) candidates.push_back({a, nearest_turn((a > 0 ? 90.0 : -90.0) - phi, from.c)});
  }
  std::optional<Index> best;
  double best_time = INFINITY, best_travel = INFINITY;
  for (Index i : candidates) {
    if (!t.a_in_range(i.a)) continue;
    // The nearest turn may lie beyond the range where another does not.
    if (!t.c_in_range(i.c)) {
      const double lo = i.c + 360.0 * std::ceil((t.c.min - i.c) / 360.0);
      if (!t.c_in_range(lo)) continue;
      i.c = lo;
    }
    const double da = std::abs(i.a - from.a), dc = std::abs(i.c - from.c);
    const double time = std::max(t.a.velocity > 0 ? da / t.a.velocity : da, t.c.velocity > 0 ? dc / t.c.velocity : dc);
    if (time < best_time - 1e-12 || (std::abs(time - best_time) <= 1e-12 && da + dc < best_travel)) {
      best = i;
      best_time = time;
      best_travel = da + dc;
    }
  }
  if (!best && why) {
    std::string needs;
    for (const Index& i : candidates) needs += (needs.empty() ? "A = " : " or A = ") + degrees(i.a);
    *why = "the tool axis needs " + needs + " degrees, outside A's range [" + degrees(t.a.min) + ", " +
           degrees(t.a.max) + "]";
  }
  return best;
}

JointSweep sweep_joints(const Trunnion& t, const Vec3& from, const Vec3& to, const Index& i0, const Index& i1) {
  const double span = std::max({(to - from).norm(), std::abs(i1.a - i0.a), std::abs(i1.c - i0.c)});
  const int n = std::isfinite(span) ? static_cast<int>(std::clamp(std::ceil(span), 1.0, 4096.0)) : 4096;
  JointSweep s;
  Vec3 before = Vec3::Zero();
  for (int k = 0; k <= n; ++k) {
    const double f = static_cast<double>(k) / n;
    const Vec3 joint = t.machine_point(from + f * (to - from), i0.a + f * (i1.a - i0.a), i0.c + f * (i1.c - i0.c));
    s.lo = s.lo.cwiseMin(joint);
    s.hi = s.hi.cwiseMax(joint);
    if (k > 0) s.travel += (joint - before).cwiseAbs();
    before = joint;
  }
  return s;
}

std::optional<std::vector<Index>> indexes_along(const Trunnion& t, const std::vector<Vec3>& axes, const Index& from,
                                                std::string* why) {
  const size_t n = axes.size();
  if (n == 0) return std::vector<Index>{};
  // Two states per axis, the solutions with A >= 0 and A <= 0; on the pole both are A = 0 with C left where it was.
  struct State {
    bool ok = false;
    double cost = INFINITY;
    Index at;
    int back = -1;
  };
  std::vector<std::array<State, 2>> dp(n);
  const auto step_cost = [&](const Index& p, const Index& q) {
    const double da = std::abs(q.a - p.a), dc = std::abs(q.c - p.c);
    return std::max(t.a.velocity > 0 ? da / t.a.velocity : da, t.c.velocity > 0 ? dc / t.c.velocity : dc) +
           1e-6 * (da + dc);
  };
  for (size_t i = 0; i < n; ++i) {
    const Vec3 d = axes[i].normalized();
    const double a0 = std::acos(std::clamp(d.z(), -1.0, 1.0)) / kDegree;
    const bool pole = d.head<2>().norm() < 1e-9;
    const double phi = std::atan2(d.y(), d.x()) / kDegree;
    for (int branch = 0; branch < 2; ++branch) {
      const double a = branch == 0 ? a0 : -a0;
      if (!t.a_in_range(a)) continue;
      State best;
      for (int prev = 0; prev < (i == 0 ? 1 : 2); ++prev) {
        const Index p = i == 0 ? from : dp[i - 1][prev].at;
        if (i > 0 && !dp[i - 1][prev].ok) continue;
        Index q{a, pole ? p.c : nearest_turn((a > 0 ? 90.0 : -90.0) - phi, p.c)};
        if (!t.c_in_range(q.c)) continue;
        const double cost = (i == 0 ? 0.0 : dp[i - 1][prev].cost) + step_cost(p, q);
        if (cost < best.cost) best = State{true, cost, q, prev};
      }
      dp[i][branch] = best;
    }
    if (!dp[i][0].ok && !dp[i][1].ok) {
      if (why)
        *why = "tool axis " + std::to_string(i) + " needs A = " + degrees(a0) + " or " + degrees(-a0) +
               " degrees, outside A's range [" + degrees(t.a.min) + ", " + degrees(t.a.max) + "]";
      return std::nullopt;
    }
  }
  int state = dp[n - 1][0].ok && (!dp[n - 1][1].ok || dp[n - 1][0].cost <= dp[n - 1][1].cost) ? 0 : 1;
  std::vector<Index> out(n);
  for (size_t i = n; i-- > 0;) {
    out[i] = dp[i][state].at;
    state = dp[i][state].back;
    if (state < 0) state = 0;
  }
  return out;
}

}  // namespace rosmill::core::machine
