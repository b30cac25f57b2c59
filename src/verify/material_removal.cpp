#include "rosmill/verify/material_removal.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "rosmill/verify/arc.hpp"
#include "rosmill/verify/cutter_profile.hpp"

namespace rosmill::verify {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr uint32_t kChordBit = 0x80000000u;

// ---- cutter profiles as functions of the squared distance from the axis (inner loops avoid a sqrt when they can)

struct FlatBottom {
  double operator()(double) const { return 0.0; }
};
struct BallBottom {
  double R, R2;
  double operator()(double d2) const { return R - std::sqrt(std::max(0.0, R2 - d2)); }
};
struct BullBottom {
  double flat, r;
  double operator()(double d2) const {
    const double e = std::sqrt(d2) - flat;
    return e <= 0 ? 0.0 : r - std::sqrt(std::max(0.0, r * r - e * e));
  }
};

// ---- one move prepared for sweeping

struct Prepared {
  bool arc = false;
  double ax, ay, az, ux, uy, uz;  // start and (end - start)
  double len2, inv_len2;           // of (ux, uy)
  double cx, cy, rho;              // arc centre and radius
  double s0x, s0y, s1x, s1y, sweep;  // arc as counter-clockwise from s0 to s1 (vectors from the centre)
  double R, R2;
  double xmin, xmax;
};

Prepared prepare(const SimMove& m, double R) {
  Prepared p{};
  p.ax = m.from.x(); p.ay = m.from.y(); p.az = m.from.z();
  p.ux = m.to.x() - p.ax; p.uy = m.to.y() - p.ay; p.uz = m.to.z() - p.az;
  p.len2 = p.ux * p.ux + p.uy * p.uy;
  p.inv_len2 = p.len2 > 0 ? 1.0 / p.len2 : 0.0;
  p.R = R; p.R2 = R * R;
  Vec2 lo, hi;
  move_xy_bounds(m, lo, hi);
  p.xmin = lo.x() - R; p.xmax = hi.x() + R;
  if (m.shape != MoveShape::Line) {
    p.arc = true;
    p.cx = m.centre.x(); p.cy = m.centre.y();
    const Vec2 a = m.from.head<2>() - m.centre, b = m.to.head<2>() - m.centre;
    p.rho = a.norm();
    const bool ccw = m.shape == MoveShape::ArcCCW;
    const Vec2& s0 = ccw ? a : b;
    const Vec2& s1 = ccw ? b : a;
    p.s0x = s0.x(); p.s0y = s0.y(); p.s1x = s1.x(); p.s1y = s1.y();
    p.sweep = std::abs(arc_sweep(m));
  }
  return p;
}

// x-interval where the row at height y meets the disc of radius R around (px, py).
void disc_row(double px, double py, double R2, double y, double& lo, double& hi) {
  const double dy = y - py, w2 = R2 - dy * dy;
  if (w2 < 0) return;
  const double w = std::sqrt(w2);
  lo = std::min(lo, px - w);
  hi = std::max(hi, px + w);
}

// Narrows [lo, hi] to the v with a·v in [L, H].
void clip_linear(double a, double L, double H, double& lo, double& hi) {
  if (a > 0) { lo = std::max(lo, L / a); hi = std::min(hi, H / a); }
  else if (a < 0) { lo = std::max(lo, H / a); hi = std::min(hi, L / a); }
  else if (L > 0 || H < 0) { lo = kInf; hi = -kInf; }
}

// x-interval of the row at height y inside the footprint: the capsule of radius R around a line (the union of
// the two end discs and the strip between them, a convex set), or the disc of radius rho + R around an arc.
bool footprint_row(const Prepared& p, double y, double& lo, double& hi) {
  lo = kInf; hi = -kInf;
  if (p.arc) {
    disc_row(p.cx, p.cy, (p.rho + p.R) * (p.rho + p.R), y, lo, hi);
    lo = std::max(lo, p.xmin); hi = std::min(hi, p.xmax);
    return lo <= hi;
  }
  disc_row(p.ax, p.ay, p.R2, y, lo, hi);
  disc_row(p.ax + p.ux, p.ay + p.uy, p.R2, y, lo, hi);
  if (p.len2 > 0) {
    const double dy = y - p.ay, len = std::sqrt(p.len2);
    double slo = -kInf, shi = kInf;
    clip_linear(p.ux, -dy * p.uy, p.len2 - dy * p.uy, slo, shi);              // 0 <= t <= 1
    clip_linear(-p.uy, -p.R * len - p.ux * dy, p.R * len - p.ux * dy, slo, shi);  // |perpendicular| <= R
    if (slo <= shi) { lo = std::min(lo, p.ax + slo); hi = std::max(hi, p.ax + shi); }
  }
  return lo <= hi;
}

// Squared XY distance from (px, py) (relative to the line start) to the segment.
inline double segment_d2(const Prepared& p, double px, double py) {
  const double t = std::clamp((px * p.ux + py * p.uy) * p.inv_len2, 0.0, 1.0);
  const double dx = px - t * p.ux, dy = py - t * p.uy;
  return dx * dx + dy * dy;
}

// ---- kernels: the lowest cutter bottom of the move over (x, y), and the squared axis distance d2

template <class Bottom>
struct LevelLine {  // z constant: the closest point of the segment is the lowest
  const Prepared& p;
  Bottom bottom;
  double operator()(double x, double y, double& d2) const {
    d2 = segment_d2(p, x - p.ax, y - p.ay);
    return d2 > p.R2 ? kInf : p.az + bottom(d2);
  }
};

struct BallRamp {  // the ball's centre sweeps a segment: its swept volume is a capsule, the lowest point exact
  const Prepared& p;
  double wx, wy, wz, L, a;  // unit 3-D direction, length, 1 - wz^2
  explicit BallRamp(const Prepared& q) : p(q) {
    L = std::sqrt(q.len2 + q.uz * q.uz);
    wx = L > 0 ? q.ux / L : 0; wy = L > 0 ? q.uy / L : 0; wz = L > 0 ? q.uz / L : 1;
    a = 1 - wz * wz;
  }
  double operator()(double x, double y, double& d2) const {
    const double ex = x - p.ax, ey = y - p.ay;
    d2 = segment_d2(p, ex, ey);
    if (d2 > p.R2) return kInf;
    double best = kInf;
    const double dA2 = ex * ex + ey * ey, fx = ex - p.ux, fy = ey - p.uy, dB2 = fx * fx + fy * fy;
    if (dA2 <= p.R2) best = p.az + p.R - std::sqrt(p.R2 - dA2);
    if (dB2 <= p.R2) best = std::min(best, p.az + p.uz + p.R - std::sqrt(p.R2 - dB2));
    if (a > 1e-12) {
      // Lower crossing of the vertical line with the cylinder of radius R around the centre's path.
      const double ew = ex * wx + ey * wy, bh = -ew * wz, c = dA2 - ew * ew - p.R2;
      const double disc = bh * bh - a * c;
      if (disc >= 0) {
        const double zr = (-bh - std::sqrt(disc)) / a;  // relative to the start centre
        const double t = (ew + zr * wz) / L;
        if (t >= 0 && t <= 1) best = std::min(best, p.az + p.R + zr);
      }
    }
    return best;
  }
};

// The part [t0, t1] of a ramp during which the axis is within R of (ex, ey); false when never.
inline bool covered_span(const Prepared& p, double ex, double ey, double& t0, double& t1) {
  const double e2 = ex * ex + ey * ey;
  if (p.len2 <= 0) { t0 = 0; t1 = 1; return e2 <= p.R2; }
  const double eu = ex * p.ux + ey * p.uy, disc = eu * eu - p.len2 * (e2 - p.R2);
  if (disc < 0) return false;
  const double s = std::sqrt(disc);
  t0 = std::max(0.0, (eu - s) * p.inv_len2);
  t1 = std::min(1.0, (eu + s) * p.inv_len2);
  return t0 <= t1;
}

struct FlatRamp {  // the flat bottom is lowest at the end of the covered span that is lower
  const Prepared& p;
  double operator()(double x, double y, double& d2) const {
    const double ex = x - p.ax, ey = y - p.ay;
    d2 = segment_d2(p, ex, ey);
    double t0, t1;
    if (d2 > p.R2 || !covered_span(p, ex, ey, t0, t1)) return kInf;
    return p.az + p.uz * (p.uz > 0 ? t0 : t1);
  }
};

struct BullRamp {  // tip height + profile is convex along the ramp: golden-section search over the covered span
  const Prepared& p;
  BullBottom bottom;
  double operator()(double x, double y, double& d2) const {
    const double ex = x - p.ax, ey = y - p.ay;
    d2 = segment_d2(p, ex, ey);
    double t0, t1;
    if (d2 > p.R2 || !covered_span(p, ex, ey, t0, t1)) return kInf;
    auto f = [&](double t) {
      const double dx = ex - t * p.ux, dy = ey - t * p.uy;
      return p.az + t * p.uz + bottom(std::min(p.R2, dx * dx + dy * dy));
    };
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    const double span_mm = std::sqrt(p.len2 + p.uz * p.uz);
    double lo = t0, hi = t1, m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo), f1 = f(m1), f2 = f(m2);
    while ((hi - lo) * span_mm > 1e-5) {
      if (f1 <= f2) { hi = m2; m2 = m1; f2 = f1; m1 = hi - g * (hi - lo); f1 = f(m1); }
      else { lo = m1; m1 = m2; f1 = f2; m2 = lo + g * (hi - lo); f2 = f(m2); }
    }
    return std::min({f(t0), f(t1), f1, f2});
  }
};

template <class Bottom>
struct LevelArc {  // z constant: the distance to the arc is |rho - |e|| inside its sweep, else to an end
  const Prepared& p;
  Bottom bottom;
  double operator()(double x, double y, double& d2) const {
    const double ex = x - p.cx, ey = y - p.cy;
    const double c0 = p.s0x * ey - p.s0y * ex, c1 = ex * p.s1y - ey * p.s1x;
    bool inside;
    if (p.sweep >= 2 * M_PI - 1e-12) inside = true;
    else if (p.sweep <= M_PI) inside = c0 >= 0 && c1 >= 0;
    else inside = !(c0 < 0 && c1 < 0);
    if (inside) {
      const double d = std::sqrt(ex * ex + ey * ey) - p.rho;
      d2 = d * d;
    } else {
      const double ax = ex - p.s0x, ay = ey - p.s0y, bx = ex - p.s1x, by = ey - p.s1y;
      d2 = std::min(ax * ax + ay * ay, bx * bx + by * by);
    }
    return d2 > p.R2 ? kInf : p.az + bottom(d2);
  }
};

// ---- sweeping one move over the rows of one band

struct Target {
  const GridSpec& g;
  float* top;
  uint32_t* cut_by;
  float* trace;  // finishing axis distance, or null when this move is not a finishing move
  uint32_t id;
  bool rapid;
  size_t* rapid_cuts;
  uint32_t* first_rapid;
};

template <class Kernel>
void sweep_rows(const Prepared& p, const Kernel& kernel, int j0, int j1, const Target& t) {
  const GridSpec& g = t.g;
  for (int j = j0; j <= j1; ++j) {
    const double y = g.cy(j);
    double lo, hi;
    if (!footprint_row(p, y, lo, hi)) continue;
    const int i0 = g.first_x(lo), i1 = g.last_x(hi);
    const size_t base = static_cast<size_t>(j) * g.nx;
    for (int i = i0; i <= i1; ++i) {
      double d2;
      const float h = static_cast<float>(kernel(g.cx(i), y, d2));
      const size_t c = base + i;
      if (t.trace && d2 <= p.R2 && d2 < t.trace[c]) t.trace[c] = static_cast<float>(d2);
      if (h < t.top[c]) {
        t.top[c] = h;
        t.cut_by[c] = t.id;
        if (t.rapid) { ++*t.rapid_cuts; *t.first_rapid = std::min(*t.first_rapid, t.id); }
      }
    }
  }
}

template <class Bottom>
void sweep_level(const Prepared& p, const Bottom& b, int j0, int j1, const Target& t) {
  if (p.arc) sweep_rows(p, LevelArc<Bottom>{p, b}, j0, j1, t);
  else sweep_rows(p, LevelLine<Bottom>{p, b}, j0, j1, t);
}

void sweep_move(const SimMove& m, const Cutter& cutter, int j0, int j1, const Target& t) {
  const CutterProfile prof = CutterProfile::of(cutter);
  const Prepared p = prepare(m, prof.radius);
  const bool level = p.uz == 0.0;  // helical arcs arrive here as chords
  switch (cutter.type) {
    case CutterType::FlatEnd:
      if (level) sweep_level(p, FlatBottom{}, j0, j1, t);
      else sweep_rows(p, FlatRamp{p}, j0, j1, t);
      break;
    case CutterType::BallEnd:
      if (level) sweep_level(p, BallBottom{prof.radius, prof.radius * prof.radius}, j0, j1, t);
      else sweep_rows(p, BallRamp(p), j0, j1, t);
      break;
    case CutterType::BullNose:
      if (level) sweep_level(p, BullBottom{prof.flat_radius, prof.corner}, j0, j1, t);
      else sweep_rows(p, BullRamp{p, BullBottom{prof.flat_radius, prof.corner}}, j0, j1, t);
      break;
  }
}

// ---- the work list: program moves in order, helical arcs replaced by their chords

struct WorkList {
  std::vector<uint32_t> items;    // program move index, or kChordBit | chord index
  std::vector<SimMove> chords;
  std::vector<uint32_t> chord_parent;
  const SimMove& move(const MachineProgram& prog, uint32_t item) const {
    return item & kChordBit ? chords[item & ~kChordBit] : prog.moves[item];
  }
  uint32_t parent(uint32_t item) const { return item & kChordBit ? chord_parent[item & ~kChordBit] : item; }
};

WorkList build_work(const MachineProgram& prog, double tolerance) {
  WorkList w;
  w.items.reserve(prog.moves.size());
  for (uint32_t k = 0; k < prog.moves.size(); ++k) {
    const SimMove& m = prog.moves[k];
    if (m.shape == MoveShape::Line || m.from.z() == m.to.z()) { w.items.push_back(k); continue; }
    // A helix: chords whose sagitta stays within the tolerance.
    const double rho = (m.from.head<2>() - m.centre).norm(), sweep = std::abs(arc_sweep(m));
    const double step = rho > tolerance ? 2 * std::acos(1 - tolerance / rho) : M_PI / 2;
    const int n = std::max(1, static_cast<int>(std::ceil(sweep / step)));
    Vec3 a = m.from;
    for (int i = 1; i <= n; ++i) {
      SimMove c = m;
      c.shape = MoveShape::Line;
      c.from = a;
      c.to = i == n ? m.to : move_point(m, static_cast<double>(i) / n);
      a = c.to;
      w.items.push_back(kChordBit | static_cast<uint32_t>(w.chords.size()));
      w.chords.push_back(c);
      w.chord_parent.push_back(k);
    }
  }
  return w;
}

}  // namespace

SimulationResult simulate(const MachineProgram& prog, Stock& stock, const SimulationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  SimulationResult result;
  result.moves = prog.moves.size();
  const GridSpec& g = stock.grid;
  result.finish_axis_d2.assign(g.cells(), std::numeric_limits<float>::infinity());
  if (prog.moves.empty() || g.cells() == 0) return result;
  // Finishing moves: the feed moves of the last tool's trailing run.
  result.finishing_tool = prog.moves.back().tool;
  size_t finish_from = prog.moves.size();
  while (finish_from > 0 && prog.moves[finish_from - 1].tool == result.finishing_tool) --finish_from;

  const WorkList work = build_work(prog, options.arc_tolerance);
  const int band_rows = std::max(1, options.band_rows);
  const int bands = (g.ny + band_rows - 1) / band_rows;
  // Rows of each work item's footprint, then the items of each band in program order (CSR).
  std::vector<int> row0(work.items.size()), row1(work.items.size());
  std::vector<uint32_t> band_start(bands + 1, 0);
  for (size_t k = 0; k < work.items.size(); ++k) {
    const SimMove& m = work.move(prog, work.items[k]);
    Vec2 lo, hi;
    move_xy_bounds(m, lo, hi);
    const double R = prog.tools[m.tool].cutter.radius();
    row0[k] = g.first_y(lo.y() - R);
    row1[k] = g.last_y(hi.y() + R);
    if (row0[k] > row1[k]) continue;
    for (int b = row0[k] / band_rows; b <= row1[k] / band_rows; ++b) ++band_start[b + 1];
  }
  for (int b = 0; b < bands; ++b) band_start[b + 1] += band_start[b];
  std::vector<uint32_t> band_items(band_start[bands]);
  {
    std::vector<uint32_t> fill(band_start.begin(), band_start.end() - 1);
    for (size_t k = 0; k < work.items.size(); ++k) {
      if (row0[k] > row1[k]) continue;
      for (int b = row0[k] / band_rows; b <= row1[k] / band_rows; ++b) band_items[fill[b]++] = static_cast<uint32_t>(k);
    }
  }

  std::vector<size_t> rapid_cuts(bands, 0);
  std::vector<uint32_t> first_rapid(bands, Stock::kNoMove);
  auto run_band = [&](int b) {
    const int r0 = b * band_rows, r1 = std::min(g.ny - 1, r0 + band_rows - 1);
    for (uint32_t q = band_start[b]; q < band_start[b + 1]; ++q) {
      const uint32_t k = band_items[q];
      const SimMove& m = work.move(prog, work.items[k]);
      const uint32_t id = work.parent(work.items[k]);
      const bool finishing = id >= finish_from && !m.rapid;
      Target t{g, stock.top.data(), stock.cut_by.data(), finishing ? result.finish_axis_d2.data() : nullptr,
               id, m.rapid, &rapid_cuts[b], &first_rapid[b]};
      sweep_move(m, prog.tools[m.tool].cutter, std::max(r0, row0[k]), std::min(r1, row1[k]), t);
    }
  };
  if (options.parallel) {
    tbb::parallel_for(tbb::blocked_range<int>(0, bands, 1), [&](const tbb::blocked_range<int>& r) {
      for (int b = r.begin(); b < r.end(); ++b) run_band(b);
    });
  } else {
    for (int b = 0; b < bands; ++b) run_band(b);
  }
  for (int b = 0; b < bands; ++b) {
    result.rapid_cut_cells += rapid_cuts[b];
    result.first_rapid_cut = std::min(result.first_rapid_cut, first_rapid[b]);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

double lowest_bottom_reference(const SimMove& move, const Cutter& cutter, double x, double y, int samples) {
  const CutterProfile prof = CutterProfile::of(cutter);
  double best = kInf;
  for (int i = 0; i <= samples; ++i) {
    const Vec3 p = move_point(move, static_cast<double>(i) / samples);
    best = std::min(best, p.z() + prof.height(std::hypot(x - p.x(), y - p.y())));
  }
  return best;
}

}  // namespace rosmill::verify
