#include "rosmill/plan/plan_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "rosmill/cutter/contact.hpp"
#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"

namespace rosmill::core {

namespace {

double resolved(double value, double fallback, const char* name) {
  const double v = std::isnan(value) ? fallback : value;
  if (!(v > 0) || !std::isfinite(v)) throw Error(std::string("parameter ") + name, "must be a positive number");
  return v;
}

}  // namespace

PlanFrame make_frame(const Surface& surface, const PlanParams& params) {
  PlanFrame f;
  f.part = surface.bounds();
  if (f.part.empty()) throw Error("plan", "the surface is empty");
  f.cutter = params.tool.cutter;
  f.stepover = resolved(params.stepover, params.tool.stepover, "stepover");
  f.stepdown = resolved(params.stepdown, params.tool.stepdown, "stepdown");
  f.tolerance = resolved(params.tolerance, kDefaultTolerance, "tolerance");
  if (!(params.allowance >= 0) || !std::isfinite(params.allowance))
    throw Error("parameter allowance", "must be >= 0");
  if (!(params.stock_margin >= 0)) throw Error("parameter stock_margin", "must be >= 0");
  if (!(params.safe_clearance > 0)) throw Error("parameter safe_clearance", "must be > 0");
  f.allowance = params.allowance;
  f.drop_cutter = offset_cutter(f.cutter, f.allowance);
  f.stock = f.part;
  f.stock.min.x() -= params.stock_margin, f.stock.min.y() -= params.stock_margin;
  f.stock.max.x() += params.stock_margin, f.stock.max.y() += params.stock_margin;
  f.stock.max.z() += params.stock_margin;
  if (params.stock_mesh) f.stock = params.stock_mesh->bbox;
  // A job's material: the levels start at its top and the safe height clears it, however high a scan stands.
  if (params.material && std::isfinite(params.material->highest())) {
    f.stock.max.z() = std::max(params.material->highest(), f.part.max.z());
    // Sideways the material's own extent (a stock turned for a setup stands out of the part differently each way).
    const Box3 m = params.material->extent();
    f.stock.min.head<2>() = m.min.head<2>().cwiseMin(f.part.min.head<2>());
    f.stock.max.head<2>() = m.max.head<2>().cwiseMax(f.part.max.head<2>());
  }
  f.safe_z = f.stock.max.z() + params.safe_clearance;
  return f;
}

double cl_height(const Surface& surface, const PlanFrame& f, double x, double y) {
  const Drop d = surface.drop(f.drop_cutter, x, y);
  return std::max(d.z, f.part.min.z()) + f.allowance;
}

MoveWriter::MoveWriter(Toolpath& tp, const PlanFrame& f) : tp_(tp), f_(f) {
  tp.safe_z = f.safe_z;
  tp.clearance_z = f.safe_z;
  tp.start = Vec3(0.5 * (f.stock.min.x() + f.stock.max.x()), 0.5 * (f.stock.min.y() + f.stock.max.y()), f.safe_z);
  pos_ = tp.start;
}

void MoveWriter::begin_pass(const std::string& name) { tp_.passes.push_back({name, {}}); }

void MoveWriter::retract() {
  if (at_safe_) return;
  pos_.z() = f_.safe_z;
  tp_.passes.back().moves.push_back({pos_, MoveType::Rapid, 0.0});
  at_safe_ = true;
}

void MoveWriter::enter(const Vec3& p, double free_z) {
  retract();
  if ((pos_.head<2>() - p.head<2>()).norm() > 0) {
    pos_ = Vec3(p.x(), p.y(), f_.safe_z);
    tp_.passes.back().moves.push_back({pos_, MoveType::Rapid, 0.0});
  }
  if (free_z < pos_.z() && free_z > p.z()) {
    pos_ = Vec3(p.x(), p.y(), free_z);
    tp_.passes.back().moves.push_back({pos_, MoveType::Feed, tp_.tool.feed});
  }
  plunge_to(p);
}

void MoveWriter::link_to(const Vec3& p, double link_z, double clear_z) {
  if (at_safe_ || !(link_z < f_.safe_z)) link_z = f_.safe_z;
  auto rapid = [&](const Vec3& to) {
    pos_ = to;
    tp_.passes.back().moves.push_back({pos_, MoveType::Rapid, 0.0});
  };
  if (pos_.z() < link_z) rapid(Vec3(pos_.x(), pos_.y(), link_z));
  if ((pos_.head<2>() - p.head<2>()).norm() > 0) rapid(Vec3(p.x(), p.y(), pos_.z()));
  if (clear_z < pos_.z() && clear_z > p.z()) rapid(Vec3(p.x(), p.y(), clear_z));
  plunge_to(p);
}

void MoveWriter::plunge_to(const Vec3& p) {
  pos_ = p;
  tp_.passes.back().moves.push_back({p, MoveType::Plunge, tp_.tool.plunge_feed});
  at_safe_ = false;
}

void MoveWriter::cut_to(const Vec3& p) {
  if (!at_safe_ && p.head<2>() == pos_.head<2>() && p.z() < pos_.z()) return plunge_to(p);
  feed(p);
}

void MoveWriter::feed(const Vec3& p) {
  if (at_safe_) return enter(p);
  if ((p - pos_).squaredNorm() == 0) return;
  pos_ = p;
  tp_.passes.back().moves.push_back({p, MoveType::Feed, tp_.tool.feed});
}

namespace {

Vec3 cl_point(const Surface& s, const PlanFrame& f, const Vec3& A, const Vec3& B, double at) {
  const Vec2 p = A.head<2>() + at * (B.head<2>() - A.head<2>());
  return Vec3(p.x(), p.y(), cl_height(s, f, p.x(), p.y()));
}

// A chord shorter than the minimum step that still misses the tolerance holds a jump of the CL height (a wall, or
// the rim of the cutter just reaching an edge) or a feature narrower than the step: it is crossed at the highest
// height sampled on it. Going up first and down last never gouges where the CL is monotone across it, as it is
// at a wall. When the path has just come down at A, it stays up instead of going straight back (a run of such
// chords, e.g. along a line at the exact rim distance from an edge, is crossed as one plateau, not as thousands
// of up-and-down steps).
void step_over(const Vec3& A, const Vec3& B, double top, std::vector<Vec3>& out) {
  const size_t n = out.size();
  if (n >= 2 && out[n - 1] == A && out[n - 2].head<2>() == A.head<2>() && out[n - 2].z() > A.z()) {
    top = std::max(top, out[n - 2].z());
    out.pop_back();
  }
  if (top > out.back().z()) out.emplace_back(A.x(), A.y(), top);
  if (top > B.z()) out.emplace_back(B.x(), B.y(), top);
  out.push_back(B);
}

// Refinement of the chord A-B, whose true CL points at a quarter, half and three quarters are q[0..2]. The
// chord stands when all three lie within half the tolerance of it; a midpoint alone is not enough, since where
// two contacts meet (a ridge) the CL can rise above the chord near one end and fall below it at the middle.
// Otherwise it is split at its midpoint, each half reusing one quarter point as its own midpoint, down to
// `min_step`: the number of drops per chord is bounded (at most 2 step / min_step), however steep the wall.
void refine(const Surface& s, const PlanFrame& f, const Vec3& A, const Vec3& B, const Vec3 (&q)[3],
            double min_step, std::vector<Vec3>& out) {
  bool within = true;
  for (int i = 0; i < 3; ++i)
    within = within && std::abs(q[i].z() - (A.z() + 0.25 * (i + 1) * (B.z() - A.z()))) <= 0.5 * f.tolerance;
  if (within) {
    out.push_back(B);
    return;
  }
  if ((B.head<2>() - A.head<2>()).norm() <= min_step) {
    step_over(A, B, std::max({A.z(), B.z(), q[0].z(), q[1].z(), q[2].z()}), out);
    return;
  }
  const Vec3& M = q[1];
  const Vec3 left[3] = {cl_point(s, f, A, M, 0.25), q[0], cl_point(s, f, A, M, 0.75)};
  refine(s, f, A, M, left, min_step, out);
  const Vec3 right[3] = {cl_point(s, f, M, B, 0.25), q[2], cl_point(s, f, M, B, 0.75)};
  refine(s, f, M, B, right, min_step, out);
}

}  // namespace

void sample_segment(const Surface& surface, const PlanFrame& f, const Vec2& a, const Vec2& b, double step,
                    std::vector<Vec3>& out) {
  const double len = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(len / step)));
  Vec3 prev(a.x(), a.y(), cl_height(surface, f, a.x(), a.y()));
  out.push_back(prev);
  for (int i = 1; i <= n; ++i) {
    const Vec2 p = a + (b - a) * (double(i) / n);
    const Vec3 cur(p.x(), p.y(), cl_height(surface, f, p.x(), p.y()));
    const Vec3 q[3] = {cl_point(surface, f, prev, cur, 0.25), cl_point(surface, f, prev, cur, 0.5),
                       cl_point(surface, f, prev, cur, 0.75)};
    refine(surface, f, prev, cur, q, kMinSampleStep, out);
    prev = cur;
  }
}

void drop_collinear(std::vector<Vec3>& pts) {
  if (pts.size() < 3) return;
  size_t w = 1;
  for (size_t i = 1; i + 1 < pts.size(); ++i) {
    const Vec3& a = pts[w - 1];
    const Vec3& b = pts[i];
    const Vec3& c = pts[i + 1];
    const Vec3 ac = c - a;
    const double len2 = ac.squaredNorm();
    const bool on_line = len2 > 0 && (b - a).cross(ac).squaredNorm() / len2 < 1e-18 && (b - a).dot(ac) >= 0 &&
                         (b - a).dot(ac) <= len2;
    if (!on_line) pts[w++] = b;
  }
  pts[w++] = pts.back();
  pts.resize(w);
}

std::vector<ScanLine> scan_lines(const Vec2& lo, const Vec2& hi, double angle_deg, double spacing,
                                 const Region& region) {
  const double a = angle_deg * M_PI / 180.0;
  const Vec2 u(std::cos(a), std::sin(a)), v(-std::sin(a), std::cos(a));
  double vmin = 1e300, vmax = -1e300;
  for (const Vec2& c : {lo, hi, Vec2(lo.x(), hi.y()), Vec2(hi.x(), lo.y())})
    vmin = std::min(vmin, c.dot(v)), vmax = std::max(vmax, c.dot(v));
  const int n = std::max(1, static_cast<int>(std::ceil((vmax - vmin) / spacing - 1e-9))) + 1;
  const double gap = n > 1 ? (vmax - vmin) / (n - 1) : 0.0;
  std::vector<ScanLine> lines;
  for (int k = 0; k < n; ++k) {
    const Vec2 origin = v * (vmin + k * gap);
    // Clip the line origin + s u to the rectangle (slabs).
    double s0 = -1e300, s1 = 1e300;
    for (int axis = 0; axis < 2; ++axis) {
      if (std::abs(u[axis]) < 1e-15) {
        if (origin[axis] < lo[axis] - 1e-12 || origin[axis] > hi[axis] + 1e-12) s0 = 1, s1 = 0;
        continue;
      }
      double t0 = (lo[axis] - origin[axis]) / u[axis], t1 = (hi[axis] - origin[axis]) / u[axis];
      if (t0 > t1) std::swap(t0, t1);
      s0 = std::max(s0, t0), s1 = std::min(s1, t1);
    }
    ScanLine line;
    if (s0 > s1) {
      lines.push_back(line);
      continue;
    }
    if (region.empty()) {
      line.pieces.emplace_back(origin + s0 * u, origin + s1 * u);
      lines.push_back(line);
      continue;
    }
    // Crossings with every loop of the region; each span between crossings is wholly inside or outside.
    std::vector<double> cuts = {s0, s1};
    for (const std::vector<Vec2>& loop : region)
      for (size_t i = 0; i < loop.size(); ++i) {
        const Vec2& p = loop[i];
        const Vec2& q = loop[(i + 1) % loop.size()];
        const double dp = (p - origin).dot(v), dq = (q - origin).dot(v);
        if ((dp > 0) == (dq > 0)) continue;
        const double s = (p + (q - p) * (dp / (dp - dq)) - origin).dot(u);
        if (s > s0 && s < s1) cuts.push_back(s);
      }
    std::sort(cuts.begin(), cuts.end());
    for (size_t i = 0; i + 1 < cuts.size(); ++i) {
      if (cuts[i + 1] - cuts[i] < 1e-9) continue;
      if (!inside_region(region, origin + 0.5 * (cuts[i] + cuts[i + 1]) * u)) continue;
      // Adjacent inside spans (split at a crossing of two loops' shared point) are one piece.
      if (!line.pieces.empty() && (line.pieces.back().second - (origin + cuts[i] * u)).norm() < 1e-9)
        line.pieces.back().second = origin + cuts[i + 1] * u;
      else
        line.pieces.emplace_back(origin + cuts[i] * u, origin + cuts[i + 1] * u);
    }
    lines.push_back(line);
  }
  return lines;
}

void check_cancel(const PlanProgress& progress, double fraction) {
  if (progress && !progress(fraction)) throw Error("plan", "cancelled");
}

void parallel_blocks(size_t n, const PlanProgress& progress, double from, double to,
                     const std::function<void(size_t)>& f) {
  const size_t block = std::max<size_t>(1, n / 50);
  for (size_t start = 0; start < n; start += block) {
    const size_t end = std::min(n, start + block);
    for_each_index(start, end, [&](size_t i) { f(i); });
    check_cancel(progress, from + (to - from) * double(end) / double(n));
  }
}

void check_plan_work(const std::string& strategy, const Work& work, const PlanFrame& f) {
  check_work(strategy, work, f.part.size().x(), f.part.size().y());
}

const char* sampling_name(Sampling s) { return s == Sampling::StepError ? "step-error" : "chord"; }

Sampling parse_sampling(const std::string& text, const std::string& where) {
  if (text == "chord") return Sampling::Chord;
  if (text == "step-error") return Sampling::StepError;
  throw Error(where, "unknown sampling '" + text + "' (chord or step-error)");
}

}  // namespace rosmill::core
