#include "rosmill/plan/adaptive.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "adaptive_regions.hpp"
#include "level_material.hpp"
#include "rosmill/cutter/chip_thinning.hpp"
#include "rosmill/cutter/contact.hpp"
#include "rosmill/error.hpp"
#include "rosmill/plan/levels.hpp"

namespace rosmill::core {
namespace {

constexpr double kAirDeg = 2.0;     // engagement below this is air: no cut to plan around
constexpr double kMeasureDeg = 2.0;  // the engagement's resolution: one sample of the half-circle
constexpr size_t kMaxRings = 20000;  // per level: a bound on the work whatever the geometry
constexpr int kStepTries = 8;        // ring step reductions before the smallest step is taken

// A closed loop of the cutter's centre sampled every `step` at most, with the direction of travel at each sample.
struct Sampled {
  std::vector<Vec2> p, dir;
  std::vector<uint8_t> vertex;  // 1 where the sample is a corner of the loop (the moves go corner to corner)
};

Sampled sample_loop(const clip::Path& path, double step) {
  Sampled s;
  const size_t n = path.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec2 a = clip::from_point(path[k]), b = clip::from_point(path[(k + 1) % n]);
    const double len = (b - a).norm();
    if (len < 1e-9) continue;
    const int parts = std::max(1, static_cast<int>(std::ceil(len / step)));
    for (int i = 0; i < parts; ++i) {
      s.p.push_back(a + (b - a) * (double(i) / parts));
      s.dir.push_back((b - a) / len);
      s.vertex.push_back(i == 0);
    }
  }
  return s;
}

// A stretch of a ring to cut: sample indices [first, first + count) of a loop, wrapping around.
struct Piece {
  size_t loop = 0, first = 0, count = 0;
};

class AdaptivePlanner {
 public:
  AdaptivePlanner(const Surface& surface, const PlanParams& params, const AdaptiveOptions& options,
                  PlanReport& report)
      : params_(params), f_(make_frame(surface, params)), profile_(f_.cutter), report_(report) {
    R_ = f_.cutter.radius();
    limit_ = engagement_limit(params, f_);
    s_max_ = R_ * (1 - std::cos(limit_ * M_PI / 180.0));
    r_min_ = std::isnan(options.min_turn_radius) ? 0.2 * R_ : options.min_turn_radius;
    helix_ = std::isnan(options.helix_radius) ? 0.5 * R_ : options.helix_radius;
    slope_ = options.ramp_slope;
    if (!(r_min_ >= 0 && r_min_ < R_)) throw Error("adaptive", "the turn radius must lie in [0, R)");
    if (!(helix_ > 0) || !(slope_ > 0)) throw Error("adaptive", "the helix radius and ramp slope must be > 0");
    cell_ = std::clamp(R_ / 20, 0.05, 0.25);
    // The rings' offsets decide engagement, not clearance of the part (every ring is cut back to the part's
    // clearance exactly), so their arcs need only a hundredth of the radius.
    arc_ = std::max(f_.tolerance, 0.01 * R_);
    // Room beside the stock for the cutter to come in from the air beside an open side.
    lo_ = f_.stock.min.head<2>() - Vec2::Constant(2 * R_ + 1);
    hi_ = f_.stock.max.head<2>() + Vec2::Constant(2 * R_ + 1);
    report_.engagement_limit_deg = limit_;
    report_.min_turn_radius = r_min_;
  }

  Job plan(const Surface& surface, const PlanProgress& progress) {
    const std::vector<double> levels = level_heights(surface);
    std::vector<std::vector<Loop>> loops;
    PlanParams loose = params_;
    // The walls need not be found closer than the rings' own arcs: a roughing leaves at most this much more.
    loose.tolerance = std::max(f_.tolerance, 0.5 * arc_);
    WaterlineOptions wo;
    wo.levels = levels;
    waterline_on(surface, loose, wo, {}, &loops);
    check_cancel(progress, 0.2);
    init_top();
    tp_.strategy = "adaptive";
    tp_.tool = params_.tool;
    MoveWriter w(tp_, f_);
    w_ = &w;
    for (size_t i = 0; i < levels.size(); ++i) {
      level(levels[i], loops[i], loose.tolerance);
      check_cancel(progress, 0.2 + 0.8 * double(i + 1) / levels.size());
    }
    w.retract();
    report_.levels = levels.size();
    return {tp_};
  }

 private:
  // ---- levels and material above them

  std::vector<double> level_heights(const Surface& surface) const {
    return roughing_levels(f_.stock.max.z(), f_.part.min.z() + f_.allowance, f_.stepdown,
                           flat_face_heights(surface, f_));
  }

  // What stands on the way of links and entries, lowered as the levels cut it: the job's material, else the stock
  // box (or the stock mesh's box) at its top.
  void init_top() {
    if (params_.material) {
      top_ = *params_.material;
      return;
    }
    top_.cell = std::max(0.5, 2 * cell_);
    top_.x0 = lo_.x(), top_.y0 = lo_.y();
    top_.nx = static_cast<int>(std::ceil((hi_.x() - lo_.x()) / top_.cell));
    top_.ny = static_cast<int>(std::ceil((hi_.y() - lo_.y()) / top_.cell));
    top_.top.assign(size_t(top_.nx) * top_.ny, -INFINITY);
    for (int j = 0; j < top_.ny; ++j)
      for (int i = 0; i < top_.nx; ++i) {
        const Vec2 c(top_.x0 + (i + 0.5) * top_.cell, top_.y0 + (j + 0.5) * top_.cell);
        // Cells that reach into the stock's box count as standing at its top.
        if (c.x() + top_.cell > f_.stock.min.x() && c.x() - top_.cell < f_.stock.max.x() &&
            c.y() + top_.cell > f_.stock.min.y() && c.y() - top_.cell < f_.stock.max.y())
          top_.top[size_t(j) * top_.nx + i] = static_cast<float>(f_.stock.max.z());
      }
  }

  // ---- one level

  void level(double z, const std::vector<Loop>& loops, double loop_tolerance) {
    PlanFrame fl = f_;
    fl.tolerance = loop_tolerance;
    const LevelRegions r = level_regions(params_, fl, z, loops, lo_, hi_, arc_, 0.0);
    if (clip::area(r.target) < 1e-3 * R_ * R_) return;
    z_ = z;
    allowed_ = r.allowed;
    target_ = r.target;
    const Vec2 big_lo = lo_ - Vec2::Constant(3 * R_), big_hi = hi_ + Vec2::Constant(3 * R_);
    cleared_ = clip::subtract(clip::rectangle(big_lo, big_hi), r.material);
    material_.emplace(big_lo, big_hi, cell_);
    material_->fill(r.target, 1);
    inside_.emplace(big_lo, big_hi, cell_);
    inside_->fill(clip::offset(r.allowed, -cell_, arc_), 1);
    given_up_.clear();
    w_->begin_pass("adaptive z " + std::to_string(z));
    double s = s_max_;
    int stalled = 0;
    for (size_t ring = 0; ring < kMaxRings && stalled < 3; ++ring) {
      const double before = material_->material_area();
      if (before < 0.01 * R_ * R_) break;
      std::vector<Sampled> loops_k;
      std::vector<Piece> pieces;
      clip::Paths q;
      s = std::min(s_max_, 1.25 * s);
      const bool cuts = next_ring(s, q, loops_k, pieces);
      skipped_ = false;
      if (cuts) {
        ++report_.rings;
        cut_ring(loops_k, pieces);
      }
      // The cleared area grows by the ring's whole region swept by the cutter (what its boundary did not cut was
      // cleared before); by what the cutter swept when a piece could not be entered.
      cleared_ = clip::simplify(clip::unite(cleared_, cuts && !skipped_ ? clip::offset(q, R_ - arc_, arc_)
                                                                        : clip::sweep(swept_, R_ - arc_, arc_)),
                                0.25 * arc_);
      swept_.clear();
      const bool progress = material_->material_area() <= before - 2 * cell_ * cell_;
      stalled = progress ? 0 : stalled + 1;
      if (!cuts || !progress)
        if (!seed()) break;
    }
    report_.left_area_mm2 += material_->material_area();
  }

  // The next ring at step s or less: the region of centres at most s beyond the cleared area, smoothed, and the
  // stretches of its boundary that meet material. False when no stretch does.
  bool next_ring(double& s, clip::Paths& q, std::vector<Sampled>& loops, std::vector<Piece>& pieces) {
    for (int attempt = 0; attempt < kStepTries; ++attempt) {
      q = clip::intersect(clip::offset(cleared_, s - R_, arc_), allowed_);
      q = clip::open(q, r_min_, arc_);
      clip::cl::CleanPolygons(q, 0.002 * clip::kScale);
      loops.clear();
      pieces.clear();
      double worst = 0;
      for (const clip::Path& path : q) {
        loops.push_back(sample_loop(path, cell_));
        worst = std::max(worst, find_pieces(loops.size() - 1, loops.back(), pieces));
      }
      if (pieces.empty()) return false;
      ring_step_ = s;
      if (worst <= limit_ + kMeasureDeg || attempt + 1 == kStepTries) return true;
      s *= 0.6;
    }
    return true;
  }

  // Appends the stretches of a loop whose leading half-circle meets material, each widened by a radius of air on
  // either side; returns the largest engagement on the loop.
  double find_pieces(size_t index, const Sampled& loop, std::vector<Piece>& pieces) const {
    const size_t n = loop.p.size();
    if (n < 3) return 0;
    std::vector<uint8_t> cuts(n);
    double worst = 0;
    for (size_t k = 0; k < n; ++k) {
      const double e = material_->engagement(loop.p[k], loop.dir[k], R_);
      // A cut, by the half-circle a cell inside the cutter's: the skin of cells a pass along a wall leaves at the
      // cutter's radius (its chords) is no cut, the material of a front is.
      cuts[k] = e > kAirDeg && material_->engagement(loop.p[k], loop.dir[k], R_ - cell_) > kAirDeg;
      worst = std::max(worst, e);
    }
    const size_t pad = static_cast<size_t>(std::ceil(R_ / cell_));
    std::vector<uint8_t> keep(n, 0);
    for (size_t k = 0; k < n; ++k)
      if (cuts[k])
        for (size_t d = 0; d <= 2 * pad; ++d) keep[(k + n + d - pad) % n] = 1;
    if (std::all_of(keep.begin(), keep.end(), [](uint8_t b) { return b; })) {
      pieces.push_back({index, 0, n + pad});  // the whole loop, closed with an overlap
      return worst;
    }
    if (std::none_of(keep.begin(), keep.end(), [](uint8_t b) { return b; })) return worst;
    // Runs of kept samples, starting after a dropped one so that no run is split at the wrap.
    size_t start = 0;
    while (keep[start]) ++start;
    for (size_t k = 1; k <= n; ++k) {
      const size_t i = (start + k) % n;
      if (keep[i] && !keep[(i + n - 1) % n]) pieces.push_back({index, i, 0});
      if (keep[i]) ++pieces.back().count;
    }
    return worst;
  }

  // ---- cutting

  // The pieces one after another: the next along the same loop when the loop's stretch between them is cleared
  // air (followed at the level instead of a lift), else the nearest.
  void cut_ring(const std::vector<Sampled>& loops, std::vector<Piece>& pieces) {
    std::vector<bool> done(pieces.size(), false);
    size_t last = pieces.size();
    for (size_t n = 0; n < pieces.size(); ++n) {
      size_t best = pieces.size();
      if (last < pieces.size())
        for (size_t i = 0; i < pieces.size(); ++i)
          if (!done[i] && pieces[i].loop == pieces[last].loop && pieces[i].count <= loops[pieces[i].loop].p.size() &&
              follow_loop(loops[pieces[i].loop], end_of(pieces[last], loops), pieces[i].first)) {
            best = i;
            break;
          }
      if (best == pieces.size()) {
        double best_d = INFINITY;
        for (size_t i = 0; i < pieces.size(); ++i) {
          if (done[i]) continue;
          const double d = (loops[pieces[i].loop].p[pieces[i].first] - w_->position().head<2>()).squaredNorm();
          if (d < best_d) best_d = d, best = i;
        }
      }
      done[best] = true;
      Piece piece = pieces[best];
      if (piece.count > loops[piece.loop].p.size()) rotate_closed(loops[piece.loop], piece);
      cut_piece(loops[piece.loop], piece);
      pieces[best] = piece;
      last = best;
    }
  }

  static size_t end_of(const Piece& piece, const std::vector<Sampled>& loops) {
    return (piece.first + piece.count) % loops[piece.loop].p.size();
  }

  // Follows the loop at the level from sample `from` (where the cutter is) to sample `to` when every step of the
  // way is clear of material; false (and no move) otherwise.
  bool follow_loop(const Sampled& loop, size_t from, size_t to) {
    const size_t n = loop.p.size();
    if (!at_level() || (loop.p[from] - w_->position().head<2>()).norm() > 1e-6) return false;
    const size_t steps = (to + n - from) % n;
    // Round the ring through air (at up to three times the feed) rather than up, across and down, unless the way
    // round is longer than the diameter twenty times over: a long closed channel's two fronts lift instead.
    if (steps * cell_ > 40 * R_) return false;
    for (size_t k = 0; k < steps; ++k)
      if (!material_->capsule_clear(loop.p[(from + k) % n], loop.p[(from + k + 1) % n], R_)) return false;
    for (size_t k = 1; k <= steps; ++k)
      if (loop.vertex[(from + k) % n] || k == steps) cut_to(loop.p[(from + k) % n]);
    return true;
  }

  // A whole loop starts where it is nearest to the cutter.
  void rotate_closed(const Sampled& loop, Piece& piece) const {
    double best = INFINITY;
    for (size_t k = 0; k < loop.p.size(); ++k) {
      const double d = (loop.p[k] - w_->position().head<2>()).squaredNorm();
      if (d < best) best = d, piece.first = k;
    }
  }

  void cut_piece(const Sampled& loop, const Piece& piece) {
    const size_t n = loop.p.size();
    size_t k = 1;
    const Vec2 start = loop.p[piece.first], t = loop.dir[piece.first];
    if (material_->disc_clear(start, R_)) {
      reach_air(start);
    } else if (!spiral_in(loop, piece, k) && !enter(start, t)) {
      skipped_ = true;
      return;
    }
    // A whole loop goes on round past where the spiral joined it: that stretch was cut short of the ring.
    const size_t end = piece.count > n ? piece.count + k : piece.count;
    for (; k <= end; ++k)
      if (loop.vertex[(piece.first + k) % n] || k == end) cut_to(loop.p[(piece.first + k) % n]);
  }

  // To p, whose disc is clear, along the level when the way is free, else from above.
  void reach_air(const Vec2& p) {
    if (at_level() && free_way(w_->position().head<2>(), p)) cut_to(p);
    else descend(p);
  }

  // Into a piece that starts in material: from the previous ring (the ring's step to its left, in cleared air)
  // onto the ring along a curve whose offset decays as exp(-x / (R sin E)): the engagement then grows as the
  // offset shrinks and never passes the limit (d/dx of the angle the cutter turns into the material equals what
  // the engagement still has to grow). Sets `k` to the sample where the piece goes on. False when the previous
  // ring is not in air there or the curve leaves the part's clearance.
  bool spiral_in(const Sampled& loop, const Piece& piece, size_t& k) {
    const size_t n = loop.p.size();
    const double rate = 0.5 / (R_ * std::max(0.2, std::sin(limit_ * M_PI / 180)));
    std::vector<Vec2> curve;
    double x = 0;
    size_t i = 0;
    for (; i <= piece.count && ring_step_ * std::exp(-rate * x) > 0.01 * R_; ++i) {
      const size_t at = (piece.first + i) % n;
      if (i > 0) x += (loop.p[at] - loop.p[(at + n - 1) % n]).norm();
      const Vec2 left(-loop.dir[at].y(), loop.dir[at].x());
      curve.push_back(loop.p[at] + ring_step_ * std::exp(-rate * x) * left);
    }
    if (curve.empty() || !material_->disc_clear(curve.front(), R_)) return false;
    if (!std::all_of(curve.begin(), curve.end(), [&](const Vec2& p) { return in_part_clearance(p); })) return false;
    reach_air(curve.front());
    for (size_t j = 1; j < curve.size(); j += 2) cut_to(curve[j]);
    k = i;
    return true;
  }

  // Brings the cutter to `start` at the level, arriving along `t` through cleared air: straight along the level,
  // else down into cleared air beside it and an arc lead-in. False when neither is possible.
  bool enter(const Vec2& start, const Vec2& t) {
    const Vec2 left(-t.y(), t.x());
    for (double rho : {std::max(r_min_, 0.5 * R_), R_, 1.5 * R_}) {
      std::vector<Vec2> arc;
      const Vec2 c = start + rho * left;
      for (int k = 9; k >= 0; --k) {
        const double psi = k * M_PI / 18;
        arc.push_back(c - rho * left * std::cos(psi) - rho * t * std::sin(psi));
      }
      if (!std::all_of(arc.begin(), arc.end(), [&](const Vec2& p) { return in_part_clearance(p); })) continue;
      if (!material_->disc_clear(arc.front(), R_)) continue;
      reach_air(arc.front());
      for (size_t k = 1; k < arc.size(); ++k) cut_to(arc[k]);
      return true;
    }
    return false;
  }


  bool at_level() const { return !w_->at_safe() && std::abs(w_->position().z() - z_) < 1e-9; }

  // A straight way along the level on which the cutter meets no material and stays out of the part.
  bool free_way(const Vec2& a, const Vec2& b) const {
    const double len = (b - a).norm();
    if (len > 8 * R_ || !material_->capsule_clear(a, b, R_)) return false;
    const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5 * cell_))));
    for (int k = 0; k <= n; ++k)
      if (!in_part_clearance(a + (b - a) * (double(k) / n))) return false;
    return true;
  }

  // p keeps the cutter out of the part: by the map of cells well inside, else exactly (a ring runs along the
  // wall, on the boundary).
  bool in_part_clearance(const Vec2& p) const { return inside_->material(p) || clip::contains(allowed_, p); }

  // Up over what stands on the way, across, down to just above the material under the cutter, and into the air
  // cleared at the level.
  void descend(const Vec2& p) {
    if (!w_->at_safe()) ++report_.lifts;
    if (!params_.material) {
      // No stock model checks the rapids: down from the safe height at the feed, through air cleared before.
      w_->enter(Vec3(p.x(), p.y(), z_), z_ + params_.approach);
    } else {
      const Vec2 from = w_->position().head<2>();
      const double over = std::max(top_.highest_along(from, p, R_) + params_.link_clearance, z_);
      const double under = top_.clear_height(p, R_, [&](double d) { return profile_.height(d); });
      w_->link_to(Vec3(p.x(), p.y(), z_), std::max(over, w_->position().z()),
                  std::max(under, z_) + params_.approach);
    }
    swept_.push_back({p});
  }

  // A feed move along the level to p: its engagement measured before it cuts, its feed from the engagement.
  void cut_to(const Vec2& p) {
    const Vec2 a = w_->position().head<2>();
    const double len = (p - a).norm();
    if (len < 1e-9) return;
    const Vec2 dir = (p - a) / len;
    double e = 0;
    const int n = std::max(1, static_cast<int>(std::ceil(len / cell_)));
    for (int k = 1; k <= n; ++k) e = std::max(e, material_->engagement(a + (p - a) * (double(k) / n), dir, R_));
    const bool joined = at_level();
    w_->feed(Vec3(p.x(), p.y(), z_));
    engagement_of_move(e);
    cut(a, p);
    if (!joined || swept_.empty()) swept_.push_back({a});
    swept_.back().push_back(p);
  }

  // The material map and the links' heights lowered where the cutter passed at the level.
  void cut(const Vec2& a, const Vec2& b, double radius = NAN) {
    const double r = std::isnan(radius) ? R_ : radius;
    material_->cut_along(a, b, r);
    top_.lower_along(a, b, r, z_, [&](double d) { return profile_.height(d); });
  }

  void engagement_of_move(double e) {
    report_.max_engagement_deg = std::max(report_.max_engagement_deg, e);
    tp_.passes.back().moves.back().feed = feed_for(e);
  }

  // Radial chip thinning (cutter/chip_thinning.hpp), capped by the machine.
  double feed_for(double e) const { return feed_for_engagement(params_.tool, e, params_.max_feed); }

  // ---- entries where no cleared air is in reach

  // A helix (or a ramp) into the material left, where it is deepest. False when none is left that an entry reaches.
  bool seed() {
    clip::Paths left = clip::subtract(target_, cleared_);
    left = clip::offset(clip::offset(left, -0.05 * R_, arc_), 0.05 * R_, arc_);
    left = clip::subtract(left, given_up_);
    if (clip::area(left) < 0.01 * R_ * R_) return false;
    const clip::Paths reach = clip::intersect(allowed_, clip::offset(left, 0.9 * R_, arc_));
    double depth = 0;
    const clip::Paths deep = deepest(reach, depth);
    if (std::none_of(deep.begin(), deep.end(), [](const clip::Path& p) { return !p.empty(); })) {
      given_up_ = clip::unite(given_up_, left);
      return false;
    }
    const Vec2 p = point_in(deep);
    const double before = material_->material_area();
    if (std::min(helix_, depth) >= std::max(0.05 * R_, 2 * cell_)) helix(p, std::min(helix_, depth));
    else if (!ramp(p)) {
      given_up_ = clip::unite(given_up_, clip::sweep({{p}}, 2 * R_, arc_));
      return true;
    }
    if (material_->material_area() > before - 0.01 * R_ * R_)
      given_up_ = clip::unite(given_up_, clip::sweep({{p}}, R_, arc_));
    return true;
  }

  // The region shrunk until a further step would leave nothing (at most to the helix radius); depth: how far.
  clip::Paths deepest(const clip::Paths& region, double& depth) const {
    clip::Paths cur = region;
    if (clip::area(cur) <= 0) return {};
    const double step = std::max(cell_, 0.125 * R_);
    while (depth < helix_) {
      const clip::Paths next = clip::offset(cur, -step, arc_);
      if (clip::area(next) < 1e-6) break;
      cur = next;
      depth += step;
    }
    return cur;
  }

  // A point inside the region: the centroid of its largest loop when inside, else a corner of it.
  static Vec2 point_in(const clip::Paths& region) {
    const clip::Path* biggest = nullptr;
    for (const clip::Path& p : region)
      if (!p.empty() && (!biggest || std::abs(clip::cl::Area(p)) > std::abs(clip::cl::Area(*biggest)))) biggest = &p;
    const size_t n = biggest->size();
    const Vec2 o = clip::from_point(biggest->front());
    Vec2 sum = Vec2::Zero();
    double twice_area = 0;
    for (size_t k = 0; k < n; ++k) {
      const Vec2 a = clip::from_point((*biggest)[k]) - o, b = clip::from_point((*biggest)[(k + 1) % n]) - o;
      const double cross = a.x() * b.y() - a.y() * b.x();
      twice_area += cross;
      sum += cross * (a + b);
    }
    const Vec2 centroid = std::abs(twice_area) > 1e-12 ? Vec2(o + sum / (3 * twice_area)) : o;
    return clip::contains(region, centroid) ? centroid : o;
  }

  void helix(const Vec2& c, double r) {
    ++report_.helices;
    constexpr int kPerTurn = 36;
    const auto at = [&](int k) -> Vec2 {
      return c + r * Vec2(std::cos(2 * M_PI * k / kPerTurn), std::sin(2 * M_PI * k / kPerTurn));
    };
    const double top = std::max(top_.highest_under(c, r + R_), z_);
    descend_to(at(0), top);
    const double drop = 2 * M_PI * r * slope_ / kPerTurn;
    int k = 0;
    for (double zc = w_->position().z(); zc > z_ + 1e-9;) {
      zc = std::max(z_, zc - drop);
      const Vec2 p = at(++k);
      w_->plunge_to(Vec3(p.x(), p.y(), zc));
    }
    // The whole disc is cut once the helix is down; a last turn at the level (still the entry, at the plunge
    // feed: it takes the wedge the last turn down left with the cutter's end) flattens its floor.
    cut(c, c, r + R_);
    for (int i = 0; i < kPerTurn; ++i) {
      const Vec2 p = at(++k);
      w_->plunge_to(Vec3(p.x(), p.y(), z_));
    }
    swept_.push_back({c});
    swept_.push_back({w_->position().head<2>()});
    cleared_ = clip::unite(cleared_, clip::sweep({{c}}, r + R_ - arc_, arc_));
  }

  // Over what stands on the way to p, down to the approach over `top`, and in at the plunge feed to `top`: the
  // start of an entry into material.
  void descend_to(const Vec2& p, double top) {
    if (!w_->at_safe()) ++report_.lifts;
    if (!params_.material) {
      w_->enter(Vec3(p.x(), p.y(), top), top + params_.approach);
      return;
    }
    const Vec2 from = w_->position().head<2>();
    const double over = std::max(top_.highest_along(from, p, R_) + params_.link_clearance, top);
    w_->link_to(Vec3(p.x(), p.y(), top), std::max(over, w_->position().z()), top + params_.approach);
  }

  // A ramp back and forth along the longest straight way through p that keeps the cutter out of the part.
  bool ramp(const Vec2& p) {
    Vec2 a = p, b = p;
    for (int k = 0; k < 36; ++k) {
      const Vec2 d(std::cos(k * M_PI / 36), std::sin(k * M_PI / 36));
      const Vec2 e0 = reach_along(p, -d), e1 = reach_along(p, d);
      if ((e1 - e0).norm() > (b - a).norm()) a = e0, b = e1;
    }
    if ((b - a).norm() < R_) return false;  // a corner's or sliver's few cells: left to rest machining
    ++report_.ramps;
    const double top = std::max(top_.highest_along(a, b, R_), z_);
    descend_to(a, top);
    const double len = (b - a).norm();
    double zc = w_->position().z();
    bool forward = true;
    while (zc > z_ + 1e-9) {
      const double drop = std::min(zc - z_, slope_ * len);
      const Vec2 from = forward ? a : b, to = forward ? b : a;
      const Vec2 q = from + (to - from) * (drop / (slope_ * len));
      zc -= drop;
      w_->plunge_to(Vec3(q.x(), q.y(), zc));
      forward = !forward;
    }
    // Along the whole way at the level, there and back (the entry's end, at the plunge feed).
    cut(a, b);
    for (const Vec2& q : {a, b, a}) w_->plunge_to(Vec3(q.x(), q.y(), z_));
    swept_.push_back({a, b});
    return true;
  }

  // The farthest point from p along d (up to 4 R) with the way there inside the part's clearance.
  Vec2 reach_along(const Vec2& p, const Vec2& d) const {
    Vec2 last = p;
    for (double s = 0.5 * cell_; s <= 4 * R_; s += 0.5 * cell_) {
      const Vec2 q = p + s * d;
      if (!in_part_clearance(q)) break;
      last = q;
    }
    return last;
  }

  const PlanParams& params_;
  PlanFrame f_;
  CutterProfile profile_;
  PlanReport& report_;
  double R_ = 0, limit_ = 0, s_max_ = 0, r_min_ = 0, helix_ = 0, slope_ = 0, cell_ = 0, arc_ = 0;
  Vec2 lo_, hi_;
  Toolpath tp_;
  MoveWriter* w_ = nullptr;
  MaterialTop top_;
  // The level being cut.
  double z_ = 0;
  clip::Paths allowed_, target_, cleared_, given_up_;
  std::vector<std::vector<Vec2>> swept_;
  bool skipped_ = false;  // a piece of the ring could not be entered
  double ring_step_ = 0;
  std::optional<LevelMaterial> material_, inside_;
};

}  // namespace

double engagement_limit(const PlanParams& params, const PlanFrame& frame) {
  if (!std::isnan(params.engagement_deg)) return params.engagement_deg;
  return side_cut_engagement_deg(frame.stepover, frame.cutter.radius());
}

Job adaptive_on(const Surface& surface, const PlanParams& params, const AdaptiveOptions& options,
                const PlanProgress& progress, PlanReport* report) {
  PlanReport local;
  AdaptivePlanner planner(surface, params, options, report ? *report : local);
  return planner.plan(surface, progress);
}

Job adaptive_strategy(const Surface& surface, const PlanParams& params, const PlanProgress& progress,
                      PlanReport* report) {
  return adaptive_on(surface, params, AdaptiveOptions{}, progress, report);
}

}  // namespace rosmill::core
