#include "rosmill/verify/engagement.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <cmath>
#include <string>

#include "recent_path.hpp"
#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/stock/material_removal.hpp"
#include "rosmill/toolpath/canon_arc.hpp"

namespace rosmill::core::verify {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kInf = INFINITY;
// A feed move whose XY travel is shorter than this (mm) goes along the tool axis: a plunge or a lift.
constexpr double kAxialMove = 1e-6;

std::string move_name(const stock::MachineProgram& program, const CanonMove& m) {
  return (program.from_gcode ? "line " : "toolpath move ") + std::to_string(m.source);
}

void check_move(const stock::MachineProgram& program, const CanonMove& m) {
  if (m.tool >= program.tools.size()) throw Error(move_name(program, m), "names a tool the program does not have");
  if (!m.from.allFinite() || !m.to.allFinite()) throw Error(move_name(program, m), "a position is not finite");
  if (m.is_arc() && m.plane != Plane::XY)
    throw Error(move_name(program, m), "only arcs in the XY plane (G17) are measured");
  if (!m.rapid && !(m.feed > 0 && std::isfinite(m.feed)))
    throw Error(move_name(program, m), "a feed move without a positive feed");
}

void check_options(const EngagementOptions& o) {
  if (!(o.cell >= 0 && o.cell <= 10)) throw Error("engagement cell", "must lie in [0, 10] mm (0: the default)");
  if (!(o.sample_step >= 0 && o.sample_step <= 10))
    throw Error("engagement sample_step", "must lie in [0, 10] mm (0: the default)");
  if (!(o.angle_step_deg >= 0.01 && o.angle_step_deg <= 10))
    throw Error("engagement angle_step_deg", "must lie in [0.01, 10] degrees");
  if (!(o.floor_tolerance >= 0 && o.floor_tolerance <= 10))
    throw Error("engagement floor_tolerance", "must lie in [0, 10] mm");
  if (o.max_cells < 1) throw Error("engagement max_cells", "must be at least 1");
}

// The smallest radius among the cutters that feed (0 when nothing feeds).
double smallest_feeding_radius(const stock::MachineProgram& program) {
  double r = 0;
  for (const CanonMove& m : program.moves)
    if (!m.rapid && m.tool < program.tools.size()) {
      const double rm = program.tools[m.tool].cutter.radius();
      r = r == 0 ? rm : std::min(r, rm);
    }
  return r;
}

// The volume of material over the stock's floor (mm^3); cells without material count as at the floor.
double volume(const stock::HeightField& stock) {
  double sum = 0;
  for (float t : stock.top) sum += std::max(0.0, double(t) - stock.bottom);
  return sum * stock.grid.cell * stock.grid.cell;
}

double feed_minutes(const stock::MachineProgram& program) {
  double minutes = 0;
  for (const CanonMove& m : program.moves)
    if (!m.rapid && m.feed > 0) minutes += move_length(m) / m.feed;
  return minutes;
}

// The XY direction of travel at fraction s of a move (zero for a move along the tool axis).
Vec2 travel_direction(const CanonMove& m, double s) {
  if (!m.is_arc()) {
    const Vec2 d = (m.to - m.from).head<2>();
    return d.norm() < kAxialMove ? Vec2::Zero() : Vec2(d.normalized());
  }
  const Vec2 r = move_point(m, s).head<2>() - m.centre;
  if (r.norm() < kAxialMove) return Vec2::Zero();
  const Vec2 tangent(-r.y(), r.x());  // counter-clockwise
  return (m.clockwise() ? -tangent : tangent).normalized();
}

// XY length of a move's path.
double xy_length(const CanonMove& m) {
  if (!m.is_arc()) return (m.to - m.from).head<2>().norm();
  return (m.from.head<2>() - m.centre).norm() * std::abs(arc_sweep(m));
}

// Reads the stock around the cutter, move by move. The stock's cells hold what the path left up to a few
// millimetres back (`lag`); the path since then is held exactly (RecentPath) and swept into the cells once the
// cutter is that far past it. Why: a path length h back the cut's edge passes the cutter's circle at its sides at
// about h cos(alpha) + h^2 / 2R (alpha from the direction of travel), so just after a cut the cells' rounding
// (cell / sqrt 2) would read a wide range of the circle near its sides as cut; a lag of 2 sqrt(R cell) keeps the
// edge of what the cells hold two cells off the circle. The exact recent path also sees an arc curl into its own
// cut (a hole milled on a circle smaller than the cutter).
class Measurer {
 public:
  Measurer(const stock::MachineProgram& program, stock::HeightField& stock, const EngagementOptions& o, double step)
      : program_(program), stock_(stock), o_(o), step_(step), sweeper_(program, stock) {
    bins_ = std::max(1, static_cast<int>(std::lround(180.0 / o.angle_step_deg)));
    bin_deg_ = 180.0 / bins_;
    for (int k = 0; k < bins_; ++k) {
      const double theta = (-90.0 + (k + 0.5) * bin_deg_) * kDeg;
      cos_.push_back(std::cos(theta));
      sin_.push_back(std::sin(theta));
    }
    length_by_count_.assign(bins_ + 1, 0.0);
    x_.resize(bins_);
    y_.resize(bins_);
    lowest_.resize(bins_);
  }

  // Measures a move before it cuts; returns its largest engagement (degrees). Unmeasured, the move only passes
  // through the stock and the recent path as a measured one would: a later chunk's measurer catches up so.
  double move(size_t index, bool measured = true) {
    const CanonMove& m = program_.moves[index];
    if (m.rapid || !m.from_known() || (!recent_.empty() && recent_.oldest().move.tool != m.tool)) flush();
    if (m.rapid || !m.from_known()) {
      sweeper_.sweep(index);
      return 0;
    }
    const double along = xy_length(m);
    if (along < kAxialMove) {
      if (measured && m.to.z() < m.from.z()) ++plunges_, plunge_mm_ += move_length(m);
      recent_.add(m, index, path_);
      return 0;
    }
    const double length = move_length(m);
    if (measured) radial_mm_ += length;
    const double R = program_.tools[m.tool].cutter.radius();
    const double lag = std::max(4 * stock_.grid.cell, 2 * std::sqrt(R * stock_.grid.cell));
    const int n = std::max(1, static_cast<int>(std::ceil(length / step_)));
    int most = 0;
    for (int i = 0; i < n; ++i) {
      const double s = (i + 0.5) / n;
      while (!recent_.empty() && recent_.oldest().end < path_ + s * along - lag) {
        sweeper_.sweep(recent_.oldest().index);
        recent_.drop_oldest();
      }
      if (measured) most = std::max(most, sample(m, s, length / n, R));
    }
    path_ += along;
    recent_.add(m, index, path_);
    return most * bin_deg_;
  }

  // Sweeps what the cells do not hold yet.
  void flush() {
    for (; !recent_.empty(); recent_.drop_oldest()) sweeper_.sweep(recent_.oldest().index);
  }

  // Adds another measurer's counts (of other moves of the same program) to this one's.
  void absorb(const Measurer& other) {
    radial_mm_ += other.radial_mm_;
    plunge_mm_ += other.plunge_mm_;
    plunges_ += other.plunges_;
    for (size_t c = 0; c < length_by_count_.size(); ++c) length_by_count_[c] += other.length_by_count_[c];
  }

  void finish(EngagementReport& r) const {
    r.radial_mm = radial_mm_;
    r.plunges = plunges_;
    r.plunge_mm = plunge_mm_;
    double below = 0;
    bool p95_found = false;
    for (int c = 0; c <= bins_; ++c) {
      const double deg = c * bin_deg_, mm = length_by_count_[c];
      if (mm <= 0) continue;
      r.max_deg = deg;
      r.histogram_mm[std::min(kEngagementBins - 1, static_cast<int>(deg / kEngagementBinDeg))] += mm;
      below += mm;
      if (!p95_found && below >= 0.95 * radial_mm_ * (1 - 1e-12)) r.p95_deg = deg, p95_found = true;
    }
  }

 private:
  // The engagement (in angle bins) at fraction s of the move, counted for `weight` mm of feed: a direction is
  // engaged where the material the cells hold there, lowered to where the recent path and this move so far passed
  // within the radius, stands above the tip.
  int sample(const CanonMove& m, double s, double weight, double R) {
    const Vec3 p = move_point(m, s);
    const Vec2 u = travel_direction(m, s);
    // Strictly within the radius: the cutter's own circle is at R from where it is now.
    const double reach = R * (1 - 1e-9) - 1e-9;
    const double floor = p.z() + o_.floor_tolerance;
    int first = bins_, last = -1;
    for (int k = 0; k < bins_; ++k) {
      const double vx = u.x() * cos_[k] - u.y() * sin_[k], vy = u.x() * sin_[k] + u.y() * cos_[k];
      x_[k] = p.x() + R * vx, y_[k] = p.y() + R * vy;
      lowest_[k] = material_at(x_[k], y_[k]) > floor ? kInf : -kInf;  // -infinity: no material, nothing to read
      if (lowest_[k] > -kInf) first = std::min(first, k), last = k;
    }
    if (last < 0) {
      length_by_count_[0] += weight;
      return 0;
    }
    for (const RecentPath::Piece& piece : recent_) lower(piece.move, 1.0, piece.disc, p, u, R, reach, first, last);
    // A line's own path so far lies straight behind the cutter, farther than the radius from every point of its
    // leading half; an arc's may curl into it.
    if (m.is_arc()) lower(m, s, footprint(m), p, u, R, reach, first, last);
    int count = 0;
    for (int k = first; k <= last; ++k) count += lowest_[k] > floor;
    length_by_count_[count] += weight;
    return count;
  }

  // Lowers the directions' readings in bins [first, last] to where `move` (up to the fraction `until`) passed within
  // reach of them. Only the bins whose points can lie within reach of the move's footprint are read: the point at
  // direction v, p + R v, lies within reach + r of the footprint's centre c exactly when the angle between v and
  // c - p is at most acos((|c - p|^2 + R^2 - (reach + r)^2) / (2 R |c - p|)) (the law of cosines). That range of
  // angles, taken a turn back and on too, meets the leading half in at most two pieces; each is widened by a bin on
  // either side so that rounding never drops a bin that the exact reading would lower.
  void lower(const CanonMove& move, double until, const Footprint& disc, const Vec3& p, const Vec2& u, double R,
             double reach, int first, int last) {
    const Vec2 e = disc.centre - p.head<2>();
    const double d = e.norm(), outer = reach + disc.radius + 1e-9;
    double w = M_PI;  // every direction
    if (d > 1e-9) {
      const double cos_w = (d * d + R * R - outer * outer) / (2 * R * d);
      if (cos_w >= 1) return;
      if (cos_w > -1) w = std::acos(cos_w);
    }
    if (w >= M_PI - 1e-9) {
      read(move, until, reach, first, last);
      return;
    }
    const double phi = std::atan2(u.x() * e.y() - u.y() * e.x(), u.dot(e));  // from u towards c, anticlockwise
    const double bin = bin_deg_ * kDeg;
    for (int turn = -1; turn <= 1; ++turn) {
      const double lo = phi - w + 2 * M_PI * turn + 0.5 * M_PI, hi = phi + w + 2 * M_PI * turn + 0.5 * M_PI;
      if (hi < -bin || lo > M_PI + bin) continue;
      read(move, until, reach, std::max(first, static_cast<int>(std::floor(lo / bin - 0.5)) - 1),
           std::min(last, static_cast<int>(std::ceil(hi / bin - 0.5)) + 1));
    }
  }

  void read(const CanonMove& move, double until, double reach, int first, int last) {
    for (int k = first; k <= last; ++k)
      if (lowest_[k] > -kInf) lowest_[k] = std::min(lowest_[k], lowest_pass_within(move, until, x_[k], y_[k],
                                                                                     reach));
  }

  // The stock's top in the cell holding (x, y); -infinity outside the grid (no material there).
  float material_at(double x, double y) const {
    const stock::GridSpec& g = stock_.grid;
    const double fi = std::floor((x - g.x0) / g.cell), fj = std::floor((y - g.y0) / g.cell);
    if (!(fi >= 0 && fj >= 0 && fi < g.nx && fj < g.ny)) return -INFINITY;
    return stock_.top[g.index(static_cast<int>(fi), static_cast<int>(fj))];
  }

  const stock::MachineProgram& program_;
  const stock::HeightField& stock_;
  const EngagementOptions& o_;
  double step_;
  stock::MoveSweeper sweeper_;
  int bins_ = 1;
  double bin_deg_ = 180;
  std::vector<double> cos_, sin_;
  std::vector<double> length_by_count_;  // feed length per number of engaged angle bins
  std::vector<double> x_, y_, lowest_;   // per bin of the sample being read: its point, how low the path passed
  RecentPath recent_;
  double path_ = 0;  // XY length of the feed path so far
  double radial_mm_ = 0, plunge_mm_ = 0;
  size_t plunges_ = 0;
};

// The moves' measuring work, in samples (a move along the axis or a rapid costs about one).
size_t samples_of(const CanonMove& m, double step) {
  if (m.rapid || !m.from_known() || xy_length(m) < kAxialMove) return 1;
  return 1 + static_cast<size_t>(std::ceil(move_length(m) / step));
}

// Where each chunk of the program starts: equal shares of the samples, as many chunks as the cores while the
// stock's copies (one per chunk) stay within a budget and each chunk has enough work to pay for its copy.
std::vector<size_t> chunk_starts(const stock::MachineProgram& program, const stock::HeightField& stock, double step) {
  constexpr size_t kCopyBudget = size_t(1) << 29;  // bytes of stock copies
  constexpr size_t kLeastSamples = 20000;          // per chunk
  const size_t copy = stock.top.size() * (sizeof(float) + sizeof(uint32_t));
  size_t total = 0;
  for (const CanonMove& m : program.moves) total += samples_of(m, step);
  size_t chunks = std::min<size_t>(max_threads(), total / kLeastSamples);
  chunks = std::max<size_t>(1, std::min(chunks, kCopyBudget / std::max<size_t>(1, copy)));
  std::vector<size_t> starts{0};
  size_t done = 0;
  for (size_t k = 0; k < program.moves.size() && starts.size() < chunks; ++k) {
    done += samples_of(program.moves[k], step);
    if (done * chunks >= total * starts.size()) starts.push_back(k + 1);
  }
  return starts;
}

}  // namespace

double engagement_cell(const stock::MachineProgram& program) {
  const double r = smallest_feeding_radius(program);
  return r > 0 ? std::min(0.1, r / 40) : 0.1;
}

double engagement_grazing_deg(double radius, double cell) {
  if (!(radius > 0)) throw Error("engagement grazing", "the cutter's radius must be > 0");
  return std::acos(std::max(-1.0, 1 - cell / (std::sqrt(2.0) * radius))) / kDeg;
}

double engagement_tolerance_deg(double radius, double cell, double angle_step_deg) {
  if (!(radius > 0)) throw Error("engagement tolerance", "the cutter's radius must be > 0");
  return cell / (std::sqrt(2.0) * radius * std::sin(30 * kDeg)) / kDeg + angle_step_deg;
}

stock::GridSpec engagement_grid(const stock::MachineProgram& program, const Box3& stock_bounds,
                                const EngagementOptions& options) {
  check_options(options);
  if (stock_bounds.empty()) throw Error("engagement grid", "the stock is empty");
  const double cell = options.cell > 0 ? options.cell : engagement_cell(program);
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
  for (const CanonMove& m : program.moves) {
    if (m.rapid || m.tool >= program.tools.size()) continue;
    Vec2 a, b;
    move_xy_bounds(m, a, b);
    const double reach = program.tools[m.tool].cutter.radius() + cell;
    lo = lo.cwiseMin(a - Vec2::Constant(reach));
    hi = hi.cwiseMax(b + Vec2::Constant(reach));
  }
  lo = lo.cwiseMax(stock_bounds.min.head<2>());
  hi = hi.cwiseMin(stock_bounds.max.head<2>());
  // No feed over the stock: one cell at its corner, which no cutter's circle reaches.
  if (!(lo.array() <= hi.array()).all()) lo = hi = stock_bounds.min.head<2>();
  return engagement_grid_over(lo, hi, cell, options.max_cells);
}

stock::GridSpec engagement_grid_over(const Vec2& lo, const Vec2& hi, double cell, size_t max_cells) {
  if (!(cell > 0) || max_cells < 1) throw Error("engagement grid", "needs a cell > 0 mm and at least one cell");
  // Coarsened until the grid's whole cells (each side rounded up, at least one) fit the limit.
  const auto cells = [&](double c) {
    return std::max(1.0, std::ceil((hi.x() - lo.x()) / c)) * std::max(1.0, std::ceil((hi.y() - lo.y()) / c));
  };
  while (cells(cell) > double(max_cells)) cell *= 1.02;
  return stock::GridSpec::covering(lo, hi, cell, max_cells, "engagement grid");
}

EngagementReport measure_engagement(const stock::MachineProgram& program, stock::HeightField& stock,
                                    const EngagementOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  check_options(options);
  for (const CanonMove& m : program.moves) check_move(program, m);
  if (stock.top.size() != stock.grid.cells())
    throw Error("engagement stock", "holds " + std::to_string(stock.top.size()) + " heights for " +
                                        std::to_string(stock.grid.cells()) + " cells");
  EngagementReport r;
  r.cell_mm = stock.grid.cell;
  const double step =
      options.sample_step > 0 ? options.sample_step : std::clamp(2 * stock.grid.cell, 0.1, 0.25);
  const double radius = smallest_feeding_radius(program);
  if (radius > 0) r.tolerance_deg = engagement_tolerance_deg(radius, r.cell_mm, options.angle_step_deg);
  const double before = volume(stock);
  // The program in chunks measured side by side, each on its own copy of the stock: a chunk's measurer first
  // passes the moves before it unmeasured (sweeping the stock is much cheaper than reading it), so that it meets
  // its chunk with the stock and the recent path a single measurer would have there, and every move reads the same.
  // The last chunk's copy ends as the whole program leaves the stock.
  const std::vector<size_t> starts = chunk_starts(program, stock, step);
  const size_t chunks = starts.size();
  std::vector<stock::HeightField> copies(chunks - 1, stock);
  std::vector<std::unique_ptr<Measurer>> measurers(chunks);
  r.move_deg.assign(program.moves.size(), 0.0f);
  for_each_index(size_t(0), chunks, [&](size_t c) {
    stock::HeightField& field = c + 1 == chunks ? stock : copies[c];
    measurers[c] = std::make_unique<Measurer>(program, field, options, step);
    Measurer& m = *measurers[c];
    const size_t end = c + 1 == chunks ? program.moves.size() : starts[c + 1];
    for (size_t k = 0; k < starts[c]; ++k) m.move(k, false);
    for (size_t k = starts[c]; k < end; ++k) r.move_deg[k] = static_cast<float>(m.move(k));
    if (c + 1 == chunks) m.flush();
  });
  for (size_t c = 1; c < chunks; ++c) measurers[0]->absorb(*measurers[c]);
  measurers[0]->finish(r);
  r.removed_mm3 = std::max(0.0, before - volume(stock));
  retime_engagement(r, program);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

void retime_engagement(EngagementReport& report, const stock::MachineProgram& program) {
  report.feed_minutes = feed_minutes(program);
  report.mrr_mm3_per_min = report.feed_minutes > 0 ? report.removed_mm3 / report.feed_minutes : 0.0;
}

}  // namespace rosmill::core::verify
