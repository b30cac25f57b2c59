#include "rosmill/plan/five_axis_finish.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/plan/ball_contact.hpp"
#include "rosmill/plan/tool_axis.hpp"

namespace rosmill::core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kApproach = 2.0;     // mm along the axis over a pass's first cutter location, at the plunge feed
constexpr double kRingStepDeg = 5.0;  // the search for a clear axis: rings this far apart round the rule's axis
constexpr int kRingAxes = 12;         // axes per ring

using Location = BallLocation;

class FiveAxisFinish {
 public:
  FiveAxisFinish(const Mesh& mesh, const PlanParams& p)
      : p_(p), tool_(p.tool), tol_(std::isnan(p.tolerance) ? kDefaultTolerance : p.tolerance),
        contact_(mesh, p.tool, p.allowance, tol_, p.safe_clearance), mesh_(mesh), R_(p.tool.cutter.radius()),
        ra_(R_ + p.allowance), lead_(p.tool_axis.lead_or_default(true)), top_(mesh.bbox.max.z()) {
    clearance_ = top_ + p.safe_clearance + R_;
  }

  Job run(const PlanProgress& progress, PlanReport* report);

 private:
  // The surface seen from above at (x, y): the point, its facet's normal and the smooth normal there.
  bool surface_at(double x, double y, Vec3& point, Vec3& facet_normal, Vec3& smooth) const {
    return contact_.surface(Vec3(x, y, top_ + 1.0), -Vec3::UnitZ(), point, facet_normal, smooth);
  }
  // The tool, its tip at `tip` and tilted along `axis`, lifted straight up (+Z) to the clearance meets nothing: spheres
  // along the ball, the shank and the holder, each a little wider than the cylinder it stands for so that together
  // they cover it, swept up.
  bool lift_clear(const Vec3& tip, const Vec3& axis) const;
  // How far up its axis the tool at this location goes before it can lift straight up; the whole way to the
  // clearance (+infinity) when no shorter one is clear.
  double lift_height(const Location& l) const;
  // The cutter location at (x, y) travelling along `travel`, by the rule and, where blocked, the search.
  // `previous`: the axis at the location before on the line (null at a run's start), which a turned axis stays near.
  Location locate(double x, double y, const Vec3& travel, const Vec3* previous, double step) const;
  // The cutter location at (x, y) with a given axis.
  Location with_axis(double x, double y, const Vec3& axis) const;
  // One raster line: its cutter locations, in runs the tool reaches without a break.
  std::vector<std::vector<Location>> line(const Vec3& from, const Vec3& dir, double length) const;
  void smooth(std::vector<Location>& run, const Vec3& from, const Vec3& dir, const std::vector<double>& s) const;
  Vec3 tip(const Location& l) const { return l.tip(R_); }

  const PlanParams& p_;
  const Tool& tool_;
  double tol_;
  BallContact contact_;
  const Mesh& mesh_;
  double R_, ra_, lead_, top_, clearance_;
  mutable std::atomic<size_t> samples_{0}, turned_{0}, unreachable_{0};
};

bool FiveAxisFinish::lift_clear(const Vec3& tip, const Vec3& axis) const {
  // Spheres of radius r a distance r apart along a cylinder of radius r cover it when grown to r * sqrt(5) / 2.
  const double grow = std::sqrt(5.0) / 2;
  const auto clear = [&](const Vec3& centre, double r) {
    const double run = clearance_ + r - centre.z();
    return run <= 0 || !(contact_.rays().first_sphere_contact(centre, Vec3::UnitZ(), r * grow, 0.0, run) < run);
  };
  const double shank = std::max(ra_, 0.5 * tool_.cutter.shank_diameter);
  const double holder_at = tool_.stick_out_mm();
  for (double s = R_; s < holder_at; s += shank)
    if (!clear(tip + s * axis, shank)) return false;
  const double holder = 0.5 * tool_.holder_mm();
  for (int k = 0; k < 3; ++k)
    if (!clear(tip + (holder_at + k * holder) * axis, holder)) return false;
  return true;
}

double FiveAxisFinish::lift_height(const Location& l) const {
  const double full = (clearance_ - tip(l).z()) / std::max(l.axis.z(), 1e-3);
  for (double h = kApproach; h < full; h *= 2)
    if (lift_clear(tip(l) + h * l.axis, l.axis)) return h;
  return kInf;
}

Location FiveAxisFinish::with_axis(double x, double y, const Vec3& axis) const {
  Vec3 point, facet, smooth;
  ++samples_;
  if (!surface_at(x, y, point, facet, smooth)) return Location{};
  return contact_.locate(point, facet, axis);
}

Location FiveAxisFinish::locate(double x, double y, const Vec3& travel, const Vec3* previous, double step) const {
  Location l;
  Vec3 point, facet, smooth;
  ++samples_;
  if (!surface_at(x, y, point, facet, smooth)) return l;
  const Vec3 target = point + ra_ * facet;
  const double cone = p_.tool_axis.cone_deg;
  const Vec3 rule = within_cone(lead_tilt_axis(smooth, travel, lead_, p_.tool_axis.tilt_deg), cone);
  l.axis = rule;
  l.left = contact_.push(target, rule, l.centre);
  if (l.left <= tol_) return l.ok = true, l;
  // Blocked: first the axis before turned towards the rule as far as the rate allows, so that a run of turned axes
  // stays smooth; then rings of axes round the rule's, nearest first: the first ring with one that reaches the
  // surface gives the axis that stands off it least, and of those the nearest to the axis before.
  if (previous) {
    const Vec3 axis = within_cone(turn_towards(*previous, rule, p_.tool_axis.rate_deg_per_mm * step), cone);
    Vec3 centre;
    const double left = contact_.push(target, axis, centre);
    if (left <= tol_) {
      l.axis = axis, l.centre = centre, l.left = left, l.turned = true, l.ok = true;
      ++turned_;
      return l;
    }
  }
  const auto nearer = [&](const Vec3& axis) {
    return previous ? angle_between_deg(axis, *previous) < angle_between_deg(l.axis, *previous) : false;
  };
  const Vec3 side = (std::abs(rule.z()) < 0.9 ? rule.cross(Vec3::UnitZ()) : rule.cross(Vec3::UnitX())).normalized();
  const Vec3 up = rule.cross(side);
  for (double ring = kRingStepDeg; ring <= 90.0 + 1e-9; ring += kRingStepDeg) {
    const double r = ring * M_PI / 180.0;
    for (int k = 0; k < kRingAxes; ++k) {
      const double phi = 2 * M_PI * k / kRingAxes;
      const Vec3 axis = within_cone(
          (std::cos(r) * rule + std::sin(r) * (std::cos(phi) * side + std::sin(phi) * up)).normalized(), cone);
      Vec3 centre;
      const double left = contact_.push(target, axis, centre);
      if (left < l.left - tol_ || (left <= l.left + tol_ && nearer(axis)))
        l.axis = axis, l.centre = centre, l.left = left;
    }
    if (l.left <= tol_) break;
  }
  // The ball stands off a point in a corner narrower than itself whatever the axis: then the rule's axis, or the
  // nearest that clears the holder, stays with the material it leaves (the report's most left).
  l.turned = (l.axis - rule).norm() > 1e-12;
  l.ok = std::isfinite(l.left);
  if (!l.ok)
    ++unreachable_;
  else if (l.turned)
    ++turned_;
  return l;
}

// The axis along a run turned no faster than the rate: a forward and a backward sweep that bring each axis within
// the rate of its neighbour. A changed axis is pushed again; where that leaves more material than the tolerance, the
// axis the rule or the search chose stays (the report's largest rate then says so).
void FiveAxisFinish::smooth(std::vector<Location>& run, const Vec3& from, const Vec3& dir,
                            const std::vector<double>& s) const {
  const size_t n = run.size();
  if (n < 2) return;
  std::vector<Vec3> axes(n);
  for (size_t i = 0; i < n; ++i) axes[i] = run[i].axis;
  const double rate = p_.tool_axis.rate_deg_per_mm;
  // An axis turned to clear the part holds, and its neighbours come round to it (a few sweeps settle both sides).
  for (int sweep = 0; sweep < 3; ++sweep) {
    for (size_t i = 1; i < n; ++i)
      if (!run[i].turned) axes[i] = turn_towards(axes[i - 1], axes[i], rate * std::abs(s[i] - s[i - 1]));
    for (size_t i = n - 1; i-- > 0;)
      if (!run[i].turned) axes[i] = turn_towards(axes[i + 1], axes[i], rate * std::abs(s[i + 1] - s[i]));
  }
  for (size_t i = 0; i < n; ++i) {
    if ((axes[i] - run[i].axis).norm() < 1e-12) continue;
    const Vec3 at = from + s[i] * dir;
    Location l = with_axis(at.x(), at.y(), axes[i]);
    if (l.ok && l.left <= std::max(tol_, run[i].left)) {
      l.turned = run[i].turned;
      run[i] = l;
    }
  }
}

std::vector<std::vector<Location>> FiveAxisFinish::line(const Vec3& from, const Vec3& dir, double length) const {
  const double step = std::min(1.0, std::max(R_ / 4, 0.05));
  const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
  return sample_runs(
      contact_, n, [&](int k) { return length * k / n; },
      [&](double at, const Location* previous) {
        const Vec3 q = from + at * dir;
        return locate(q.x(), q.y(), dir, previous ? &previous->axis : nullptr, length / n);
      },
      [&](double at, const Vec3& axis) {
        const Vec3 q = from + at * dir;
        return with_axis(q.x(), q.y(), axis);
      },
      [&](std::vector<Location>& run, const std::vector<double>& s) { smooth(run, from, dir, s); });
}

Job FiveAxisFinish::run(const PlanProgress& progress, PlanReport* report) {
  const double stepover = std::isnan(p_.stepover) ? tool_.stepover : p_.stepover;
  const double angle = p_.angle_deg * M_PI / 180.0;
  const Vec3 u(std::cos(angle), std::sin(angle), 0), v(-std::sin(angle), std::cos(angle), 0);
  // The part's extent along and across the lines.
  double ulo = kInf, uhi = -kInf, vlo = kInf, vhi = -kInf;
  for (int c = 0; c < 4; ++c) {
    const Vec3 corner(c & 1 ? mesh_.bbox.max.x() : mesh_.bbox.min.x(), c & 2 ? mesh_.bbox.max.y() : mesh_.bbox.min.y(),
                      0);
    ulo = std::min(ulo, corner.dot(u)), uhi = std::max(uhi, corner.dot(u));
    vlo = std::min(vlo, corner.dot(v)), vhi = std::max(vhi, corner.dot(v));
  }
  const int lines = std::max(1, static_cast<int>(std::ceil((vhi - vlo) / stepover)) + 1);
  const double first = 0.5 * (vlo + vhi) - 0.5 * (lines - 1) * stepover;
  std::vector<std::vector<std::vector<Location>>> found(lines);
  std::atomic<int> done{0};
  std::atomic<bool> cancelled{false};
  for_each_piece(0, lines, 1, [&](int begin, int end) {
    for (int k = begin; k < end && !cancelled; ++k) {
      // Zigzag: every other line runs back.
      const bool back = k % 2 == 1;
      const double across = first + k * stepover;
      const Vec3 start = (back ? uhi : ulo) * u + across * v;
      found[k] = line(start, back ? Vec3(-u) : u, uhi - ulo);
      if (progress && !progress(static_cast<double>(++done) / lines)) cancelled = true;
    }
  });
  if (cancelled) throw Error("plan", "cancelled");

  Toolpath tp;
  tp.strategy = "five-axis";
  tp.tool = tool_;
  tp.tool.stepover = stepover;  // the passes' own, which a verifier's scallop theory reads
  tp.safe_z = tp.clearance_z = clearance_;
  tp.tolerance = tol_;
  AxisFigures figures;
  for (int k = 0; k < lines; ++k)
    for (const std::vector<Location>& run : found[k]) {
      ToolpathPass pass;
      pass.name = "line " + std::to_string(k);
      auto add = [&](const Vec3& to, const Vec3& axis, MoveType type, double feed) {
        pass.moves.push_back(Move{to, type, feed});
        pass.axes.push_back(axis);
      };
      // In and out along the first and the last location's axis, which the sweep found free, as far as the tool
      // must go before it can move straight down or up (lift_height); the whole way to the clearance otherwise.
      // Below the clearance every move is a feed but the lift (the limits check does not know the space is free).
      const Location& a = run.front();
      const Location& b = run.back();
      const auto out_along = [&](const Location& l, double h) {
        return std::isfinite(h) ? Vec3(tip(l) + h * l.axis)
                                : Vec3(tip(l) + (clearance_ - tip(l).z()) / std::max(l.axis.z(), 1e-3) * l.axis);
      };
      const auto above = [&](const Vec3& q) { return Vec3(q.x(), q.y(), std::max(q.z(), clearance_)); };
      const double ha = lift_height(a), hb = lift_height(b);
      const Vec3 in = out_along(a, ha), out = out_along(b, hb);
      if (tp.passes.empty()) tp.start = above(in);
      add(above(in), a.axis, MoveType::Rapid, 0);
      if (std::isfinite(ha)) add(in, a.axis, MoveType::Feed, tool_.feed);
      if (std::isfinite(ha) && ha > kApproach) add(tip(a) + kApproach * a.axis, a.axis, MoveType::Feed, tool_.feed);
      add(tip(a), a.axis, MoveType::Plunge, tool_.plunge_feed);
      add_cuts(pass, run, R_, tool_.feed, figures);
      add(out, b.axis, MoveType::Feed, tool_.feed);
      if (std::isfinite(hb)) add(above(out), b.axis, MoveType::Rapid, 0);
      tp.passes.push_back(std::move(pass));
    }
  report_axes(report, tp, static_cast<size_t>(lines), samples_, turned_, unreachable_, figures);
  if (tp.passes.empty())
    throw Error("five-axis", "no cutter location reaches the part (" + std::to_string(unreachable_) +
                                 " the holder or shank cannot reach)");
  return {std::move(tp)};
}

}  // namespace

Job five_axis_finish(const Mesh& mesh, const PlanParams& params, const PlanProgress& progress, PlanReport* report) {
  check_ball_finishing(mesh, params.tool, "five-axis");
  FiveAxisFinish planner(mesh, params);
  return planner.run(progress, report);
}

}  // namespace rosmill::core
