#include "rosmill/plan/four_axis_finish.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/plan/ball_contact.hpp"

namespace rosmill::core {
namespace {

constexpr double kApproach = 2.0;     // mm along the axis over a ring's first cutter location, at the plunge feed
constexpr double kTurnStepDeg = 5.0;  // the search for a clear axis: turns about Z this far apart
constexpr double kMaxTurnDeg = 60.0;

class FourAxisFinish {
 public:
  FourAxisFinish(const Mesh& mesh, const PlanParams& p)
      : p_(p), tool_(p.tool), tol_(std::isnan(p.tolerance) ? kDefaultTolerance : p.tolerance),
        contact_(mesh, p.tool, p.allowance, tol_, p.safe_clearance), mesh_(mesh), R_(p.tool.cutter.radius()),
        lead_(p.tool_axis.lead_or_default(true)) {
    for (int c = 0; c < 4; ++c)
      reach_ = std::max(
          reach_,
          Vec2(c & 1 ? mesh.bbox.max.x() : mesh.bbox.min.x(), c & 2 ? mesh.bbox.max.y() : mesh.bbox.min.y()).norm());
  }

  Job run(const PlanProgress& progress, PlanReport* report);

 private:
  // The cutter location on the ring at height z and angle theta (radians), by the rule or with `given` axis.
  BallLocation locate(double z, double theta, const Vec3* given) const;
  std::vector<std::vector<BallLocation>> ring(double z) const;

  const PlanParams& p_;
  const Tool& tool_;
  double tol_;
  BallContact contact_;
  const Mesh& mesh_;
  double R_, lead_, reach_ = 0;
  mutable std::atomic<size_t> samples_{0}, turned_{0}, unreachable_{0};
};

BallLocation FourAxisFinish::locate(double z, double theta, const Vec3* given) const {
  ++samples_;
  const Vec3 u(std::cos(theta), std::sin(theta), 0);
  Vec3 point, facet, smooth;
  if (!contact_.surface(Vec3(0, 0, z) + (reach_ + 2 * R_ + 1) * u, -u, point, facet, smooth)) return {};
  if (given) return contact_.locate(point, facet, *given);
  // The normal's part across the rotary axis, turned there by the lead towards travel (counter-clockwise).
  Vec3 across(smooth.x(), smooth.y(), 0);
  across = across.norm() > 1e-9 ? Vec3(across.normalized()) : u;
  const Vec3 travel = Vec3::UnitZ().cross(across);
  const double lead = lead_ * M_PI / 180;
  const Vec3 rule = std::cos(lead) * across + std::sin(lead) * travel;
  BallLocation best = contact_.locate(point, facet, rule);
  if (best.left <= tol_) return best;
  // Blocked or standing off: the axis turned about Z either way, nearest first.
  for (double turn = kTurnStepDeg; turn <= kMaxTurnDeg + 1e-9; turn += kTurnStepDeg) {
    for (const double side : {1.0, -1.0}) {
      const Vec3 axis = Eigen::AngleAxisd(side * turn * M_PI / 180, Vec3::UnitZ()) * rule;
      const BallLocation l = contact_.locate(point, facet, axis);
      if (l.ok && l.left < best.left - tol_) best = l, best.turned = true;
    }
    if (best.left <= tol_) break;
  }
  if (!best.ok)
    ++unreachable_;
  else if (best.turned)
    ++turned_;
  return best;
}

std::vector<std::vector<BallLocation>> FourAxisFinish::ring(double z) const {
  const double step = std::min(1.0, std::max(R_ / 4, 0.05));
  const int n = std::max(12, static_cast<int>(std::ceil(2 * M_PI * reach_ / step)));
  // The whole turn, its last location the first again.
  return sample_runs(
      contact_, n, [&](int k) { return 2 * M_PI * k / n; },
      [&](double theta, const BallLocation*) { return locate(z, theta, nullptr); },
      [&](double theta, const Vec3& axis) { return locate(z, theta, &axis); });
}

Job FourAxisFinish::run(const PlanProgress& progress, PlanReport* report) {
  const double stepover = std::isnan(p_.stepover) ? tool_.stepover : p_.stepover;
  const double bottom = mesh_.bbox.min.z() + 0.5 * tool_.holder_mm() + p_.safe_clearance;
  const double top = mesh_.bbox.max.z();
  if (!(bottom < top))
    throw Error("four-axis", "the part is lower than the holder's radius over the table (" +
                                 std::to_string(bottom - mesh_.bbox.min.z()) + " mm): no ring fits");
  // Rings half a stepover apart from the top and the bottom: none grazes the top face.
  const int rings = std::max(1, static_cast<int>(std::floor((top - bottom) / stepover + 0.5)));
  std::vector<std::vector<std::vector<BallLocation>>> found(rings);
  std::atomic<int> done{0};
  std::atomic<bool> cancelled{false};
  for_each_piece(0, rings, 1, [&](int begin, int end) {
    for (int k = begin; k < end && !cancelled; ++k) {
      found[k] = ring(top - (k + 0.5) * stepover);
      if (progress && !progress(static_cast<double>(++done) / rings)) cancelled = true;
    }
  });
  if (cancelled) throw Error("plan", "cancelled");

  Toolpath tp;
  tp.strategy = "four-axis";
  tp.tool = tool_;
  tp.tool.stepover = stepover;  // the rings' own, which a verifier's scallop theory reads
  tp.clearance_z = tp.safe_z = contact_.free_bounds().max.z();
  tp.tolerance = tol_;
  AxisFigures figures;
  for (int k = 0; k < rings; ++k)
    for (const std::vector<BallLocation>& run : found[k]) {
      ToolpathPass pass;
      pass.name = "ring " + std::to_string(k);
      const auto add = [&](const Vec3& to, const Vec3& axis, MoveType type, double feed) {
        pass.moves.push_back(Move{to, type, feed});
        pass.axes.push_back(axis);
      };
      // In along the first location's axis from the free space round the part (which its sweep found clear), out
      // along the last's; between rings along the side of that space, level with the tool's axis.
      const BallLocation& a = run.front();
      const BallLocation& b = run.back();
      const Vec3 in = a.tip(R_) + contact_.run_out(a.tip(R_), a.axis, 0) * a.axis;
      const Vec3 out = b.tip(R_) + contact_.run_out(b.tip(R_), b.axis, 0) * b.axis;
      if (tp.passes.empty()) tp.start = Vec3(in.x(), in.y(), tp.clearance_z);
      add(in, a.axis, MoveType::Rapid, 0);
      add(a.tip(R_) + kApproach * a.axis, a.axis, MoveType::Feed, tool_.feed);
      add(a.tip(R_), a.axis, MoveType::Plunge, tool_.plunge_feed);
      add_cuts(pass, run, R_, tool_.feed, figures);
      add(out, b.axis, MoveType::Feed, tool_.feed);
      tp.passes.push_back(std::move(pass));
    }
  report_axes(report, tp, static_cast<size_t>(rings), samples_, turned_, unreachable_, figures);
  if (tp.passes.empty())
    throw Error("four-axis", "no ring round the part's Z axis reaches it (" + std::to_string(unreachable_) +
                                 " locations the holder or shank cannot reach): is the part's axis the program's Z "
                                 "through its origin?");
  return {std::move(tp)};
}

}  // namespace

Job four_axis_finish(const Mesh& mesh, const PlanParams& params, const PlanProgress& progress, PlanReport* report) {
  check_ball_finishing(mesh, params.tool, "four-axis");
  FourAxisFinish planner(mesh, params);
  return planner.run(progress, report);
}

}  // namespace rosmill::core
