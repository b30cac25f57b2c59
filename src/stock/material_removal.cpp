#include "rosmill/stock/material_removal.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "sweep_kernels.hpp"

// How a chain of moves is swept without visiting each move's whole footprint.
//
// Along a chain (moves of one tool, each starting where the last ended) the cutter's bottom over a cell is a
// continuous function F of the position along the chain, convex along each line (z is linear along it and every
// profile is a convex, rising function of the distance to the axis, itself convex along a line). Its lowest value
// is therefore at a local minimum: inside a line where the line's own minimum lies (its lead, sweep_geometry.hpp,
// between 0 and L), at a joint where the line before still falls (lead past its end) and the line after already
// rises (lead before its start), or at an end of the chain. A line is swept only over the cells where it holds one
// of those: a strip about as wide as the line is long, instead of a disc of the cutter's diameter. Arcs, bull
// noses on ramps and rapids are swept whole (a rapid must be, to catch a crash into material the instant it
// happens); a line after them skips only the cells whose bottom rises from its start (their lowest is the joint,
// which the whole sweep before covered). The finishing trace (distance to the finishing path) is kept the same
// way with the nearest point for lead. SimulationOptions::prune = false sweeps every move whole: the reference.

namespace rosmill::core::stock {
namespace {

using namespace sweep;

// A piece of a move swept as one: a line (or a chord of a helix), or a level XY arc.
struct Piece {
  const CanonMove* move = nullptr;
  bool arc = false;
  LineFrame line;
  bool pruned = false;  // swept only where it can hold its chain's lowest point
  Lead lead;
};

bool lead_of(const LineFrame& f, const CutterProfile& cp, Lead& lead) {
  switch (cp.type) {
    case CutterType::FlatEnd: lead = {f.uz < 0 ? -1.0 : 1.0, cp.R}; return true;
    case CutterType::BallEnd: lead = {f.kz, cp.R}; return true;
    case CutterType::BullNose: lead = {1.0, cp.R1}; return f.uz == 0;
  }
  return false;
}

Piece line_piece(const CanonMove& m, const Vec3& from, const Vec3& to, const CutterProfile& cp, bool prune) {
  Piece p;
  p.move = &m;
  p.line = line_frame(from, to);
  p.pruned = prune && !m.rapid && lead_of(p.line, cp, p.lead);
  return p;
}

// A bound on how far past a line's end (in its lead g) the joint with the next line can hold a lowest point:
// where the next line's lead is <= 0, g - L = g' + (g - L - g'), and over the disc of radius R around the joint
// |g - L - g'| <= R |u - u'| + |k - k'| rho + |k'| R sqrt(2 |u - u'|) (u, u' the XY directions; |sqrt x - sqrt y|
// <= sqrt |x - y|). So the joint is swept as the strip of this line widened by that much: for a smooth path, by
// almost nothing.
double joint_margin(const Piece& p, const Piece& next, double R) {
  const double du = std::hypot(p.line.ux - next.line.ux, p.line.uy - next.line.uy);
  return R * du + std::abs(p.lead.kappa - next.lead.kappa) * p.lead.rho +
         std::abs(next.lead.kappa) * R * std::sqrt(2 * du);
}

// Chords of a helix (an arc whose z changes) within `tolerance` of it: made where they are swept, never stored,
// and at most kMaxChords of them however large the arc (the error then stays below 1e-6 of its radius).
constexpr int kMaxChords = 4096;

int chord_count(const CanonMove& m, double tolerance) {
  const double rho = (m.from.head<2>() - m.centre).norm(), sweep = std::abs(arc_sweep(m));
  const double step = rho > tolerance ? 2 * std::acos(1 - tolerance / rho) : M_PI / 2;
  return std::clamp(static_cast<int>(std::ceil(sweep / step)), 1, kMaxChords);
}

bool is_helix(const CanonMove& m) { return m.shape != MoveShape::Line && m.from.z() != m.to.z(); }

Vec3 chord_end(const CanonMove& m, int i, int n) { return i == n ? m.to : move_point(m, static_cast<double>(i) / n); }

// ---- one band of rows: its moves in program order

class BandSweep {
 public:
  BandSweep(const MachineProgram& prog, const std::vector<CutterProfile>& profiles, const SimulationOptions& o,
            HeightField& stock, float* trace, double trace_radius, int r0, int r1)
      : prog_(prog), profiles_(profiles), o_(o), g_(stock.grid), top_(stock.top.data()),
        cut_by_(stock.cut_by.data()), trace_(trace), trace_radius_(trace_radius), r0_(r0), r1_(r1) {}

  // Sweeps move k; `linked`: it starts where move k - 1 (same tool, same finishing state) ended; `next_linked`
  // the same for move k + 1. Returns the cells it lowered.
  size_t move(uint32_t k, bool linked, bool next_linked, bool finishing) {
    const CanonMove& m = prog_.moves[k];
    const CutterProfile& cp = profiles_[m.tool];
    const float trace_d2 = static_cast<float>(std::min(trace_radius_, cp.R) * std::min(trace_radius_, cp.R));
    const Target t{top_, cut_by_, finishing ? trace_ : nullptr, k, cp.R2, trace_d2};
    if (m.shape != MoveShape::Line && !is_helix(m)) {
      Piece arc;
      arc.move = &m;
      arc.arc = true;
      return sweep_arc(arc, cp, t);
    }
    // A line's piece was usually made already, as the next piece of the move before.
    const Piece current =
        m.shape == MoveShape::Line && cached_ == k ? cached_piece_ : line_piece(m, m.from, m.to, cp, o_.prune);
    Piece next;
    const Piece* after = next_linked && first_piece(k + 1, next) ? &next : nullptr;
    if (after) cached_ = k + 1, cached_piece_ = next;
    if (m.shape == MoveShape::Line) return sweep_line(current, linked, after, cp, t);
    const int n = chord_count(m, o_.arc_tolerance);
    size_t lowered = 0;
    Vec3 a = m.from, b = chord_end(m, 1, n);
    for (int i = 1; i <= n; ++i) {
      const Piece p = line_piece(m, a, b, cp, o_.prune);
      Piece chord;
      const Vec3 c = i < n ? chord_end(m, i + 1, n) : b;
      if (i < n) chord = line_piece(m, b, c, cp, o_.prune);
      lowered += sweep_line(p, linked || i > 1, i < n ? &chord : after, cp, t);
      a = b;
      b = c;
    }
    return lowered;
  }

  size_t cells_visited() const { return visited_; }

 private:
  // The first piece of move k (false for a level arc, which is swept whole, or past the end).
  bool first_piece(size_t k, Piece& p) const {
    if (k >= prog_.moves.size()) return false;
    const CanonMove& m = prog_.moves[k];
    const CutterProfile& cp = profiles_[m.tool];
    if (m.shape == MoveShape::Line) { p = line_piece(m, m.from, m.to, cp, o_.prune); return true; }
    if (!is_helix(m)) return false;
    p = line_piece(m, m.from, chord_end(m, 1, chord_count(m, o_.arc_tolerance)), cp, o_.prune);
    return true;
  }

  // Rows of the band that a disc of radius R around the XY segment from p to q can reach.
  void rows(double y0, double y1, double R, int& j0, int& j1) const {
    j0 = std::max(r0_, g_.first_y(std::min(y0, y1) - R));
    j1 = std::min(r1_, g_.last_y(std::max(y0, y1) + R));
  }

  // The cells of a row to sweep, as index ranges (at most four spans, merged). Each span is grown by a hair so
  // that a cell centre exactly on the boundary between two lines' strips, computed twice with rounding, is swept.
  struct Spans {
    int lo[4], hi[4], n = 0;
    void add(const GridSpec& g, double x0, double x1) {
      if (!(x0 <= x1)) return;
      const int i0 = g.first_x(x0 - 1e-9), i1 = g.last_x(x1 + 1e-9);
      if (i0 <= i1) { lo[n] = i0; hi[n] = i1; ++n; }
    }
    void merge() {
      for (int a = 1; a < n; ++a)  // insertion sort by start: n <= 4
        for (int b = a; b > 0 && lo[b] < lo[b - 1]; --b) std::swap(lo[b], lo[b - 1]), std::swap(hi[b], hi[b - 1]);
      int m = 0;
      for (int a = 0; a < n; ++a) {
        if (m > 0 && lo[a] <= hi[m - 1] + 1) hi[m - 1] = std::max(hi[m - 1], hi[a]);
        else lo[m] = lo[a], hi[m] = hi[a], ++m;
      }
      n = m;
    }
  };

  size_t sweep_line(const Piece& p, bool linked, const Piece* next, const CutterProfile& cp, const Target& t) {
    const LineFrame& f = p.line;
    int j0, j1;
    rows(f.ay, f.ay + f.L * f.uy, cp.R, j0, j1);
    const double w = std::min(trace_radius_, cp.R);
    const bool chain_start = !linked;
    // The lead range to sweep: from the start (chain start) or 0, to the end (chain end) or L widened by the joint
    // margin; a joint with a vertical move is swept on its own (its lead is infinite).
    const bool joint_vertical = next && next->pruned && next->line.vertical;
    const double gmin = chain_start ? -kInf : 0.0;
    const double gmax = !(next && next->pruned) ? kInf : joint_vertical ? f.L : f.L + joint_margin(p, *next, cp.R);
    const bool trace_next = next && next->pruned && !next->line.vertical;
    const double tmax = trace_next ? f.L + w * std::hypot(f.ux - next->line.ux, f.uy - next->line.uy) : kInf;
    // A whole sweep after a linked move leaves alone the cells whose bottom rises from the start (a <= skip).
    double skip = -kInf;
    if (!p.pruned && linked && o_.prune) {
      if (f.vertical < 0) return 0;  // a retract from where the last move left the cutter
      if (!f.vertical && f.uz >= 0) skip = 0;
      else if (!f.vertical && cp.type == CutterType::BallEnd) skip = f.kz * cp.R;  // the ball's contact trails
    }
    size_t lowered = 0;
    for (int j = j0; j <= j1; ++j) {
      const double y = g_.cy(j);
      Spans s;
      double lo, hi;
      if (!p.pruned || f.vertical) {
        if (!capsule_row(f, cp.R, y, lo, hi)) continue;
        if (!p.pruned) {
          if (skip > -kInf) clip_along(f, y, skip, kInf, lo, hi);
          s.add(g_, lo, hi);
        } else {
          double a = lo, b = hi;
          clip_lead(f, p.lead, y, gmin, gmax, a, b);
          s.add(g_, a, b);
          if (f.vertical > 0 && next && next->pruned) {  // going down, then the next line rises from its foot
            a = lo, b = hi;
            clip_lead(next->line, next->lead, y, -kInf, 0, a, b);
            s.add(g_, a, b);
          }
          if (t.trace && chain_start && capsule_row(f, w, y, lo, hi)) s.add(g_, lo, hi);
        }
      } else {
        // Cells within R across the line (the kernels leave alone those beyond R of it), then the lead range.
        lo = -kInf, hi = kInf;
        clip_across(f, y, cp.R, lo, hi);
        clip_along(f, y, -cp.R, f.L + cp.R, lo, hi);
        double a = lo, b = hi;
        clip_lead(f, p.lead, y, gmin, gmax, a, b, 2 * g_.cell);
        s.add(g_, a, b);
        if (joint_vertical) {
          a = lo, b = hi;
          clip_lead(f, p.lead, y, f.L, kInf, a, b);
          clip_lead(next->line, next->lead, y, -kInf, 0, a, b);
          s.add(g_, a, b);
        }
        if (t.trace) {
          a = -kInf, b = kInf;
          clip_across(f, y, w, a, b);
          clip_along(f, y, std::max(gmin, -w), std::min(tmax, f.L + w), a, b);
          s.add(g_, a, b);
        }
      }
      s.merge();
      const size_t base = g_.index(0, j);
      for (int q = 0; q < s.n; ++q) {
        visited_ += s.hi[q] - s.lo[q] + 1;
        lowered += line_row(f, cp, y, s.lo[q], s.hi[q], base, t);
      }
    }
    return lowered;
  }

  uint32_t line_row(const LineFrame& f, const CutterProfile& cp, double y, int i0, int i1, size_t base,
                    const Target& t) const {
    const RowFrame r(f, g_, y);
    const bool level = f.uz == 0.0;
    switch (cp.type) {
      case CutterType::FlatEnd:
        return level ? update(LevelLineRow<FlatProfile>{f, r, {}}, i0, i1, base, t)
                     : update(FlatRampRow{f, r, cp.R2}, i0, i1, base, t);
      case CutterType::BallEnd:
        return level ? update(LevelLineRow<BallProfile>{f, r, {cp.R, cp.R2}}, i0, i1, base, t)
                     : update(BallRampRow{f, r, cp.R, cp.R2}, i0, i1, base, t);
      case CutterType::BullNose:
        return level ? update(LevelLineRow<BullProfile>{f, r, {cp.R1, cp.r, cp.r * cp.r}}, i0, i1, base, t)
                     : update(BullRampRow(f, g_, y, cp), i0, i1, base, t);
    }
    return 0;
  }

  size_t sweep_arc(const Piece& p, const CutterProfile& cp, const Target& t) {
    const ArcFrame a = arc_frame(*p.move);
    int j0, j1;
    rows(a.cy - a.rho, a.cy + a.rho, cp.R, j0, j1);
    size_t lowered = 0;
    for (int j = j0; j <= j1; ++j) {
      const double y = g_.cy(j);
      double lo, hi;
      if (!arc_row(a, cp.R, y, lo, hi)) continue;
      const int i0 = g_.first_x(lo), i1 = g_.last_x(hi);
      if (i0 > i1) continue;
      visited_ += i1 - i0 + 1;
      const size_t base = g_.index(0, j);
      const double ex0 = g_.cx(0) - a.cx, ey = y - a.cy;
      switch (cp.type) {
        case CutterType::FlatEnd:
          lowered += update(LevelArcRow<FlatProfile>{a, ex0, g_.cell, ey, cp.R2, {}}, i0, i1, base, t);
          break;
        case CutterType::BallEnd:
          lowered += update(LevelArcRow<BallProfile>{a, ex0, g_.cell, ey, cp.R2, {cp.R, cp.R2}}, i0, i1, base, t);
          break;
        case CutterType::BullNose:
          lowered += update(LevelArcRow<BullProfile>{a, ex0, g_.cell, ey, cp.R2, {cp.R1, cp.r, cp.r * cp.r}}, i0,
                            i1, base, t);
          break;
      }
    }
    return lowered;
  }

  const MachineProgram& prog_;
  const std::vector<CutterProfile>& profiles_;
  const SimulationOptions& o_;
  const GridSpec& g_;
  float* top_;
  uint32_t* cut_by_;
  float* trace_;
  double trace_radius_;
  int r0_, r1_;
  size_t visited_ = 0;
  uint32_t cached_ = HeightField::kNoMove;  // the move whose first piece cached_piece_ is
  Piece cached_piece_;
};

}  // namespace

SimulationResult simulate(const MachineProgram& prog, HeightField& stock, const SimulationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  SimulationResult result;
  result.moves = prog.moves.size();
  const GridSpec& g = stock.grid;
  if (options.trace_finishing) result.finish_axis_d2.assign(g.cells(), std::numeric_limits<float>::infinity());
  if (prog.moves.empty() || g.cells() == 0) return result;
  // Finishing moves: the feed moves of the last tool's trailing run.
  result.finishing_tool = prog.moves.back().tool;
  size_t finish_from = prog.moves.size();
  while (finish_from > 0 && prog.moves[finish_from - 1].tool == result.finishing_tool) --finish_from;
  auto finishing = [&](size_t k) { return k >= finish_from && !prog.moves[k].rapid; };

  std::vector<CutterProfile> profiles;
  for (const Tool& tool : prog.tools) profiles.emplace_back(tool.cutter);
  const double trace_radius = options.trace_radius > 0 ? options.trace_radius : kInf;
  const int band_rows = std::max(1, options.band_rows);
  const int bands = (g.ny + band_rows - 1) / band_rows;
  // Rows of each move's footprint, then the moves of each band in program order (CSR).
  const size_t n = prog.moves.size();
  std::vector<int> row0(n), row1(n);
  std::vector<uint8_t> linked(n + 1, 0);
  std::vector<uint32_t> band_start(bands + 1, 0);
  for (size_t k = 0; k < n; ++k) {
    const CanonMove& m = prog.moves[k];
    Vec2 lo, hi;
    move_xy_bounds(m, lo, hi);
    const double R = profiles[m.tool].R;
    row0[k] = g.first_y(lo.y() - R);
    row1[k] = g.last_y(hi.y() + R);
    if (k > 0) {
      const CanonMove& p = prog.moves[k - 1];
      linked[k] = p.tool == m.tool && p.to == m.from && finishing(k) == finishing(k - 1);
    }
    if (row0[k] > row1[k]) continue;
    for (int b = row0[k] / band_rows; b <= row1[k] / band_rows; ++b) ++band_start[b + 1];
  }
  for (int b = 0; b < bands; ++b) band_start[b + 1] += band_start[b];
  std::vector<uint32_t> band_moves(band_start[bands]);
  {
    std::vector<uint32_t> fill(band_start.begin(), band_start.end() - 1);
    for (size_t k = 0; k < n; ++k) {
      if (row0[k] > row1[k]) continue;
      for (int b = row0[k] / band_rows; b <= row1[k] / band_rows; ++b) band_moves[fill[b]++] = static_cast<uint32_t>(k);
    }
  }

  // Bands write a move's mark independently (a move spans several bands): relaxed atomic stores of the same 1.
  std::unique_ptr<std::atomic<uint8_t>[]> marks;
  if (options.mark_cutting_moves) {
    marks.reset(new std::atomic<uint8_t>[n]);
    for (size_t k = 0; k < n; ++k) marks[k].store(0, std::memory_order_relaxed);
  }
  std::vector<size_t> rapid_cuts(bands, 0), visited(bands, 0);
  std::vector<uint32_t> first_rapid(bands, HeightField::kNoMove);
  auto run_band = [&](int b) {
    const int r0 = b * band_rows, r1 = std::min(g.ny - 1, r0 + band_rows - 1);
    float* trace = options.trace_finishing ? result.finish_axis_d2.data() : nullptr;
    BandSweep sweep(prog, profiles, options, stock, trace, trace_radius, r0, r1);
    for (uint32_t q = band_start[b]; q < band_start[b + 1]; ++q) {
      const uint32_t k = band_moves[q];
      const size_t lowered = sweep.move(k, linked[k], linked[k + 1], finishing(k));
      if (lowered && marks) marks[k].store(1, std::memory_order_relaxed);
      if (prog.moves[k].rapid && lowered) {
        rapid_cuts[b] += lowered;
        first_rapid[b] = std::min(first_rapid[b], k);
      }
    }
    visited[b] = sweep.cells_visited();
  };
  if (options.parallel) {
    for_each_piece<int>(0, bands, 1, [&](int begin, int end) {
      for (int b = begin; b < end; ++b) run_band(b);
    });
  } else {
    for (int b = 0; b < bands; ++b) run_band(b);
  }
  for (int b = 0; b < bands; ++b) {
    result.rapid_cut_cells += rapid_cuts[b];
    result.first_rapid_cut = std::min(result.first_rapid_cut, first_rapid[b]);
    result.cells_visited += visited[b];
  }
  if (marks) {
    result.cutting_moves.resize(n);
    for (size_t k = 0; k < n; ++k) result.cutting_moves[k] = marks[k].load(std::memory_order_relaxed);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

// The sweeper runs one band of every row over the program, its moves in order, pruned as simulate() prunes them.
struct MoveSweeper::State {
  const MachineProgram& program;
  std::vector<CutterProfile> profiles;
  SimulationOptions options;
  HeightField& stock;
  BandSweep band;
  size_t next = 0;  // the move to sweep next
  State(const MachineProgram& prog, HeightField& field, double arc_tolerance)
      : program(prog), profiles(cutter_profiles(prog)), options(sweep_options(arc_tolerance)),
        stock(with_marks(field)), band(prog, profiles, options, field, nullptr, kInf, 0, std::max(0, field.grid.ny - 1)) {}
  static std::vector<CutterProfile> cutter_profiles(const MachineProgram& program) {
    std::vector<CutterProfile> out;
    for (const Tool& tool : program.tools) out.emplace_back(tool.cutter);
    return out;
  }
  static HeightField& with_marks(HeightField& field) {
    if (field.cut_by.size() != field.top.size()) field.cut_by.assign(field.top.size(), HeightField::kNoMove);
    return field;
  }
  static SimulationOptions sweep_options(double arc_tolerance) {
    SimulationOptions o;
    o.arc_tolerance = arc_tolerance;
    o.parallel = false;
    o.trace_finishing = false;
    return o;
  }
  // As simulate() links them (no finishing trace: every move counts as not finishing).
  bool linked(size_t k) const {
    if (k == 0 || k >= program.moves.size()) return false;
    const CanonMove& p = program.moves[k - 1];
    const CanonMove& m = program.moves[k];
    return p.tool == m.tool && p.to == m.from;
  }
};

MoveSweeper::MoveSweeper(const MachineProgram& program, HeightField& stock, double arc_tolerance)
    : state_(std::make_unique<State>(program, stock, arc_tolerance)) {}

MoveSweeper::~MoveSweeper() = default;

size_t MoveSweeper::sweep(size_t k) {
  State& s = *state_;
  if (k != s.next)
    throw Error("move sweeper", "asked for move " + std::to_string(k) + " where move " + std::to_string(s.next) +
                                    " is next");
  s.next = k + 1;
  if (s.stock.grid.cells() == 0) return 0;
  const CanonMove& m = s.program.moves[k];
  if (m.tool >= s.profiles.size())
    throw Error("program move " + std::to_string(m.source), "names a tool the program does not have");
  return s.band.move(static_cast<uint32_t>(k), s.linked(k), s.linked(k + 1), false);
}

double lowest_bottom_reference(const CanonMove& move, const Cutter& cutter, double x, double y, int samples) {
  const CutterProfile cp(cutter);
  double best = kInf;
  for (int i = 0; i <= samples; ++i) {
    const Vec3 p = move_point(move, static_cast<double>(i) / samples);
    const double d = std::hypot(x - p.x(), y - p.y());
    if (d <= cp.R) best = std::min(best, p.z() + cp.height(d));
  }
  return best;
}

}  // namespace rosmill::core::stock
