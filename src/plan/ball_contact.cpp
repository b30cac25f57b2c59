#include "rosmill/plan/ball_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "rosmill/error.hpp"
#include "rosmill/geometry/corner_normals.hpp"
#include "rosmill/plan/tool_axis.hpp"

namespace rosmill::core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kMaxRefine = 10;  // halvings of a step between two cutter locations

}  // namespace

BallContact::BallContact(const Mesh& mesh, const Tool& tool, double allowance, double tolerance, double margin)
    : mesh_(mesh), rays_(mesh), normals_(corner_normals(mesh)), tool_(tool), R_(tool.cutter.radius()),
      ra_(R_ + allowance), tol_(tolerance) {
  free_ = mesh.bbox;
  const Vec3 grow = Vec3::Constant(margin + ra_);
  free_.min -= grow;
  free_.max += grow;
}

bool BallContact::surface(const Vec3& origin, const Vec3& direction, Vec3& point, Vec3& facet_normal,
                          Vec3& smooth) const {
  uint32_t f = kNone;
  const double t = rays_.first_hit(origin, direction, 0.0, kInf, &f);
  if (!std::isfinite(t) || f == kNone) return false;
  point = origin + t * direction;
  facet_normal = mesh_.normals[f];
  if (facet_normal.dot(direction) >= 0) return false;  // met from behind: the mesh's inside, or a wall edge-on
  // Barycentric weights of the point on the facet (for the smooth normal).
  const Vec3 a = mesh_.corner(f, 0), e1 = mesh_.corner(f, 1) - a, e2 = mesh_.corner(f, 2) - a, w = point - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), w1 = w.dot(e1), w2 = w.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  const double u = det > 0 ? (d22 * w1 - d12 * w2) / det : 0, v = det > 0 ? (d11 * w2 - d12 * w1) / det : 0;
  smooth = smooth_normal(normals_, f, u, v);
  return true;
}

double BallContact::run_out(const Vec3& p, const Vec3& axis, double r) const {
  // The ray's exit from the grown bounds (slab test), plus the radius.
  double exit = kInf;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(axis[a]) < 1e-15) continue;
    const double bound = axis[a] > 0 ? free_.max[a] : free_.min[a];
    exit = std::min(exit, (bound - p[a]) / axis[a]);
  }
  return std::max(0.0, exit) + r;
}

bool BallContact::swept_clear(const Vec3& end, const Vec3& axis, double r) const {
  const double run = run_out(end, axis, r);
  return !(rays_.first_sphere_contact(end + run * axis, -axis, r, 0.0, run) < run - 1e-9);
}

double BallContact::push(const Vec3& target, const Vec3& axis, Vec3& centre) const {
  const double run = run_out(target, axis, ra_);
  const Vec3 start = target + run * axis;
  const double t = std::min(run, rays_.first_sphere_contact(start, -axis, ra_, 0.0, run));
  centre = start - t * axis;
  if (!shank_and_holder_clear(centre, axis)) return kInf;
  return run - t;
}

// A shank wider than the ball, and the holder, swept down the axis to where they stand with the ball at `centre`
// (their lower ends' centres: conservative by a sphere's cap).
bool BallContact::shank_and_holder_clear(const Vec3& centre, const Vec3& axis) const {
  const double shank = 0.5 * tool_.cutter.shank_diameter;
  if (shank > ra_ && !swept_clear(centre + (tool_.cutter.flute_length - R_) * axis, axis, shank)) return false;
  return swept_clear(centre + (tool_.stick_out_mm() - R_) * axis, axis, 0.5 * tool_.holder_mm());
}

BallLocation BallContact::locate(const Vec3& point, const Vec3& facet_normal, const Vec3& axis) const {
  BallLocation l;
  l.axis = axis;
  l.left = push(point + ra_ * facet_normal, axis, l.centre);
  l.ok = std::isfinite(l.left);
  return l;
}

bool BallContact::body_clear(const Vec3& centre, const Vec3& axis) const {
  return swept_clear(centre, axis, ra_ - tol_) && shank_and_holder_clear(centre, axis);
}

bool BallContact::gouges(const Vec3& centre) const {
  return rays_.first_sphere_contact(centre, Vec3::UnitZ(), ra_ - tol_, 0.0, 0.0) == 0.0;
}

bool BallContact::touches(const Vec3& centre, double slack) const {
  return rays_.first_sphere_contact(centre, Vec3::UnitZ(), ra_ + tol_ + slack, 0.0, 0.0) == 0.0;
}

void refine_between(const BallContact& contact, const BallLocation& a, const BallLocation& b, double sa, double sb,
                    const std::function<BallLocation(double, const Vec3&)>& between, std::vector<BallLocation>& out,
                    bool& broke, int depth) {
  const double R = contact.radius();
  const double sm = 0.5 * (sa + sb);
  const Vec3 axis = (a.axis + b.axis).normalized();
  // The ball halfway along the move, where the controller puts it.
  const Vec3 halfway = 0.5 * (a.tip(R) + b.tip(R)) + R * axis;
  const bool gouges = contact.gouges(halfway) || !contact.body_clear(halfway, axis);
  if (!gouges && contact.touches(halfway, std::max(a.left, b.left))) {
    out.push_back(b);
    return;
  }
  const BallLocation m = between(sm, axis);
  if (!m.ok || depth >= kMaxRefine) {  // the tool does not reach between them, or never closely enough
    if (gouges || !m.ok) {
      broke = true;
      return;
    }
    out.push_back(b);
    return;
  }
  refine_between(contact, a, m, sa, sm, between, out, broke, depth + 1);
  if (broke) return;
  refine_between(contact, m, b, sm, sb, between, out, broke, depth + 1);
}

void refine_run(const BallContact& contact, const std::vector<BallLocation>& run, const std::vector<double>& at,
                const std::function<BallLocation(double, const Vec3&)>& between,
                std::vector<std::vector<BallLocation>>& runs) {
  if (run.size() < 2) return;
  std::vector<BallLocation> fine = {run.front()}, piece;
  for (size_t i = 1; i < run.size(); ++i) {
    bool broke = false;
    piece.clear();
    refine_between(contact, run[i - 1], run[i], at[i - 1], at[i], between, piece, broke);
    if (broke) {
      if (fine.size() >= 2) runs.push_back(std::move(fine));
      fine = {run[i]};
      continue;
    }
    fine.insert(fine.end(), piece.begin(), piece.end());
  }
  if (fine.size() >= 2) runs.push_back(std::move(fine));
}

std::vector<std::vector<BallLocation>> sample_runs(
    const BallContact& contact, int n, const std::function<double(int)>& at,
    const std::function<BallLocation(double, const BallLocation*)>& locate,
    const std::function<BallLocation(double, const Vec3&)>& between,
    const std::function<void(std::vector<BallLocation>&, const std::vector<double>&)>& adjust) {
  std::vector<std::vector<BallLocation>> runs;
  std::vector<BallLocation> run;
  std::vector<double> params;
  const auto close = [&]() {
    if (adjust) adjust(run, params);
    refine_run(contact, run, params, between, runs);
    run.clear();
    params.clear();
  };
  for (int k = 0; k <= n; ++k) {
    const double s = at(k);
    const BallLocation l = locate(s, run.empty() ? nullptr : &run.back());
    if (!l.ok) {
      close();
      continue;
    }
    run.push_back(l);
    params.push_back(s);
  }
  close();
  return runs;
}

void add_cuts(ToolpathPass& pass, const std::vector<BallLocation>& run, double radius, double feed, AxisFigures& f) {
  for (size_t i = 0; i < run.size(); ++i) {
    const BallLocation& l = run[i];
    f.max_tilt_deg = std::max(f.max_tilt_deg, angle_between_deg(l.axis, Vec3::UnitZ()));
    f.max_left_mm = std::max(f.max_left_mm, l.left);
    if (i == 0) continue;
    pass.moves.push_back(Move{l.tip(radius), MoveType::Feed, feed});
    pass.axes.push_back(l.axis);
    const double len = (l.tip(radius) - run[i - 1].tip(radius)).norm();
    if (len > 1e-9)
      f.max_rate_deg_per_mm = std::max(f.max_rate_deg_per_mm, angle_between_deg(l.axis, run[i - 1].axis) / len);
  }
}

void report_axes(PlanReport* r, const Toolpath& tp, size_t lines, size_t samples, size_t turned, size_t unreachable,
                 const AxisFigures& f) {
  if (!r) return;
  r->strategy = tp.strategy;
  r->lines = lines;
  r->samples = samples;
  r->cl_points = tp.move_count();
  r->max_tilt_deg = f.max_tilt_deg;
  r->max_axis_rate_deg_per_mm = f.max_rate_deg_per_mm;
  r->axes_turned_to_clear = turned;
  r->unreachable_points = unreachable;
  r->max_left_mm = f.max_left_mm;
}

void check_ball_finishing(const Mesh& mesh, const Tool& tool, const std::string& strategy) {
  if (tool.cutter.type != CutterType::BallEnd)
    throw Error(strategy, strategy +
                              " finishing takes a ball end mill (a tilted flat or bull-nose cutter's contact "
                              "with the mesh is not written yet): give --tool ball:D");
  if (mesh.face_count() == 0) throw Error(strategy, "the mesh has no facets");
  check_has_area(mesh, strategy);
}

}  // namespace rosmill::core
