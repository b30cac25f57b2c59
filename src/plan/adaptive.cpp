#include "rosmill/plan/adaptive.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "adaptive_regions.hpp"
#include "body_guard.hpp"
#include "rosmill/cutter/chip_thinning.hpp"
#include "rosmill/cutter/contact.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/dubins.hpp"
#include "rosmill/geometry/region_lookup.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/plan/level_material.hpp"
#include "rosmill/plan/levels.hpp"

namespace rosmill::core {
namespace {

constexpr double kAirDeg = 2.0;       // engagement below this is air: no cut to steer by
constexpr double kMeasureDeg = 2.0;   // the engagement's resolution: one sample of the half-circle
constexpr int kHelixPerTurn = 36;     // points of a helix turn
constexpr double kWallRoom = 0.5;     // turn radii a pass keeps ahead of it clear of the walls
constexpr double kWalkBack = 4.0;     // cutter radii a start is walked back along its front at most
constexpr int kMinPassSteps = 3;      // steps (R / 10 each) a pass cuts for at least
constexpr double kAirTurn = 2 * M_PI / 3;  // the most a pass turns in air between two cuts
constexpr int kTurns = 64;            // a step turns to one of kTurns + 1, from fully away to fully into the material
constexpr int kEscapeSteps = 2;       // steps turning away a pass keeps open after each step
constexpr size_t kMaxSteps = 2000000;  // per level: a bound on the work whatever the geometry
constexpr size_t kStepsPerEntry = 1000;  // what an entry's search counts for against kMaxSteps
constexpr int kMaxFailedEntries = 32;     // per level
constexpr double kMaxSteerDeg = 90.0;     // the most engagement a pass is steered to, whatever the limit

// h turned by a radians (counter-clockwise).
Vec2 turned(const Vec2& h, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * h.x() - s * h.y(), s * h.x() + c * h.y()};
}

// h turned by the angle whose cosine and sine are cs.
Vec2 turned_by(const Vec2& h, const Vec2& cs) {
  return {cs.x() * h.x() - cs.y() * h.y(), cs.y() * h.x() + cs.x() * h.y()};
}

// Where a pass begins: the cutter's centre in cleared air beside the material, and the direction it sets off in.
struct Start {
  Vec2 p, h;
  size_t cell = 0;  // the edge cell it was placed beside
};

// One step of a steered path: the cutter's next centre, its heading there, and whether its engagement passes the
// target.
struct Step {
  Vec2 p, h;
  bool over = false;
  // The way out was tried from here and is open: the next step turned fully away, the first of that way, is
  // under the target (and stays so, as cutting only takes material away).
  bool escapes = false;
  // The turn taken, of steer()'s grid: where the next step's searches begin, as a pass along a front or a wall
  // turns about as much from step to step.
  int turn = kTurns;
};

// The last of the turns [lo, hi) that passes, where lo passes and hi fails (or lies past the grid), searched from
// the hint outward by doubling strides and then halving: a step near the hint takes two or three measures where
// halving [lo, hi) takes six. Where passing is monotone in the turn (the engagement grows as the turn goes into
// the material) it is the one turn before the first that fails, as halving finds.
template <class Passes>
int last_passing(int lo, int hi, int hint, const Passes& passes) {
  if (hi - lo <= 1) return lo;
  const int k = std::clamp(hint, lo + 1, hi - 1);
  if (passes(k)) {
    lo = k;
    for (int d = 1; lo + d < hi; d *= 2) {
      if (!passes(lo + d)) {
        hi = lo + d;
        break;
      }
      lo += d;
    }
  } else {
    hi = k;
    for (int d = 1; hi - d > lo; d *= 2) {
      if (passes(hi - d)) {
        lo = hi - d;
        break;
      }
      hi -= d;
    }
  }
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (passes(mid) ? lo : hi) = mid;
  }
  return lo;
}

class AdaptivePlanner {
 public:
  AdaptivePlanner(const Surface& surface, const PlanParams& params, const AdaptiveOptions& options,
                  PlanReport& report)
      : params_(params), f_(make_frame(surface, params)), profile_(f_.cutter), report_(report) {
    R_ = f_.cutter.radius();
    limit_ = engagement_limit(params, f_);
    r_min_ = std::isnan(options.min_turn_radius) ? 0.2 * R_ : options.min_turn_radius;
    helix_ = std::isnan(options.helix_radius) ? 0.75 * R_ : options.helix_radius;
    slope_ = options.ramp_slope;
    if (!(r_min_ >= 0 && r_min_ < R_)) throw Error("adaptive", "the turn radius must lie in [0, R)");
    if (!(helix_ > 0) || !(slope_ > 0)) throw Error("adaptive", "the helix radius and ramp slope must be > 0");
    if (!(limit_ > kAirDeg + kMeasureDeg))
      throw Error("adaptive", "the engagement limit must be over " + std::to_string(kAirDeg + kMeasureDeg) +
                                  " degrees (a stepover of more than 0.1 % of the diameter)");
    // Cells fine enough for the engagement: a third of the step of a straight side cut at the limit (a 2 %
    // step-over of a 6 mm cutter is 0.12 mm), and a twentieth of the radius.
    cell_ = std::clamp(std::min(R_ / 20, R_ * (1 - std::cos(limit_ * M_PI / 180)) / 3), 0.02, 0.25);
    step_ = std::max(cell_, 0.1 * R_);
    // A step turns the heading by at most step / r_min: the path's curvature stays under 1 / r_min.
    max_turn_ = std::min(0.5 * M_PI, r_min_ > 0 ? step_ / r_min_ : 0.5 * M_PI);
    for (int k = 0; k <= kTurns; ++k) {
      const double a = -max_turn_ * (2.0 * k / kTurns - 1);  // steer()'s turn k with the material on the right
      turns_[k] = Vec2(std::cos(a), std::sin(a));
    }
    // Steered to at most kMaxSteerDeg: past a side cut of half the tool, turning into the material as far as the
    // limit allows winds a pass round its own track (at a slotting limit of 180, circles of the turn radius).
    target_ = std::min(limit_, kMaxSteerDeg) - kMeasureDeg;
    // A pass sets off from air toward the front it is to cut at a slant: it meets the front at about the slant
    // plus the cut's own angle, so the slant stays well under the target.
    lead_in_ = std::min(M_PI / 12, 0.25 * target_ * M_PI / 180);
    arc_ = std::max(f_.tolerance, 0.01 * R_);
    // Room beside the stock for the cutter to come in from the air beside an open side.
    lo_ = f_.stock.min.head<2>() - Vec2::Constant(2 * R_ + 1);
    hi_ = f_.stock.max.head<2>() + Vec2::Constant(2 * R_ + 1);
    report_.engagement_limit_deg = limit_;
    report_.min_turn_radius = r_min_;
  }

  Job plan(const Surface& surface, const PlanProgress& progress) {
    surface_ = &surface;
    const std::vector<double> levels = level_heights(surface);
    std::vector<std::vector<Loop>> loops(levels.size());
    PlanParams loose = params_;
    // The walls need not be found closer than the offsets' own arcs: a roughing leaves at most this much more.
    loose.tolerance = std::max(f_.tolerance, 0.5 * arc_);
    const WaterlineWalls part_walls(surface, loose, levels.size());
    // The walls of levels [from, to).
    const auto walls = [&](size_t from, size_t to) {
      if (from >= to) return;
      std::vector<std::vector<Loop>> found =
          part_walls.loops(std::vector<double>(levels.begin() + long(from), levels.begin() + long(to)));
      std::move(found.begin(), found.end(), loops.begin() + long(from));
    };
    // The first level's walls first. Meanwhile the level maps' memory is made the process's own on the other core:
    // a virtual machine's host faults each fresh page in (heap_reuse.hpp), and the maps are megabytes.
    TaskGroup maps;
    maps.run([&] { reserve_maps(); });
    walls(0, 1);
    maps.wait();
    // The regions of a level: what is to be cleared there and where the cutter may go. They depend on the walls and
    // the stock the job gives, not on what the levels above cut.
    std::vector<LevelRegions> regions(levels.size());
    const auto regions_of = [&](size_t i) {
      PlanFrame fl = f_;
      fl.tolerance = loose.tolerance;
      regions[i] = level_regions(params_, fl, levels[i], loops[i], lo_, hi_, arc_, 0.0);
    };
    // The other levels' walls and regions are found on the other core while the first level is planned (one core:
    // a pass follows the last), and are waited for only after it.
    TaskGroup others;
    others.run([&] {
      walls(1, levels.size());
      for (size_t i = 1; i < levels.size(); ++i) regions_of(i);
    });
    regions_of(0);
    check_cancel(progress, 0.2);
    init_top();
    tp_.strategy = "adaptive";
    tp_.tool = params_.tool;
    MoveWriter w(tp_, f_);
    w_ = &w;
    for (size_t i = 0; i < levels.size(); ++i) {
      if (i == 1) others.wait();
      level(levels[i], regions[i]);
      check_cancel(progress, 0.2 + 0.8 * double(i + 1) / levels.size());
    }
    others.wait();
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

  // The box a level's maps cover: the work area and a cutter's reach beyond.
  Vec2 map_lo() const { return lo_ - Vec2::Constant(3 * R_); }
  Vec2 map_hi() const { return hi_ + Vec2::Constant(3 * R_); }

  // Every level's maps at their size, written once (see plan()); a level then rewrites them in place.
  void reserve_maps() {
    material_.reset(map_lo(), map_hi(), cell_);
    const size_t n = size_t(material_.nx()) * material_.ny();
    given_up_.assign(n, 0);
    closed_.assign(n, 0);
    const long f = coarse_cells();
    for (std::vector<float>& s : scratch_) s.assign(size_t(material_.nx() / f + 1) * size_t(material_.ny() / f + 1), 0);
  }

  void level(double z, const LevelRegions& r) {
    if (clip::area(r.target) < 1e-3 * R_ * R_) return;
    z_ = z;
    allowed_ = r.allowed;
    // The shank and holder keep off what the levels above left (beside the walls, in corners), as zigzag
    // roughing's do: where they would meet it the cutter may not go.
    if (params_.material) guard_.at_level(top_, params_.tool, f_.allowance, z);
    const Vec2 big_lo = map_lo(), big_hi = map_hi();
    // The material map and the lookup of where the cutter may go, side by side (isolated: waiting for the other,
    // this thread takes none of the other levels' walls, which may be being found meanwhile).
    isolated([&] {
      run_both(
          [&] {
            material_.reset(big_lo, big_hi, cell_);
            material_.fill(clip::subtract(clip::rectangle(big_lo, big_hi), r.material), LevelMaterial::kAir);
            material_.fill(r.target, LevelMaterial::kMaterial);
          },
          [&] { allowed_lookup_ = RegionLookup(r.allowed, 4 * cell_); });
    });
    given_up_.assign(size_t(material_.nx()) * material_.ny(), 0);
    give_up_skin();
    steps_ = 0;
    failed_entries_ = 0;
    w_->begin_pass("adaptive z " + std::to_string(z));
    // Passes of at least kMinPassSteps first; then, where material is left that only shorter passes reach (a
    // front too tight for the turn radius), those too, from every start again.
    for (int min_steps : {kMinPassSteps, 1}) {
      min_steps_ = min_steps;
      while (steps_ < kMaxSteps && material_.material_area() > 0) {
        const std::optional<Start> start = next_start();
        if (start) {
          pass(*start);
        } else {
          steps_ += kStepsPerEntry;  // an entry's search is the work of many steps: bounded as they are
          if (!seed()) break;
        }
      }
      if (material_.material_area_off_walls(2) <= R_ * step_) break;
      std::fill(given_up_.begin(), given_up_.end(), 0);
      give_up_skin();
    }
    wall_pass();
    take_pins();
    // Where the passes and the wall pass left material they reach (a channel whose centres have no room for a
    // pass at the limit, a corner the walls' turn radius rounds), the wall pass again, as a slot: at whatever
    // engagement, at the feed that keeps the chip load there (chip_thinning.hpp), stated in the report.
    if (material_.material_area_off_walls(2) > 0.01 * R_ * R_) {
      slotting_ = true;
      wall_pass();
      slotting_ = false;
    }
    report_.left_area_mm2 += material_.material_area_off_walls(2);
    report_left(r);
  }

  // ---- what a level left, and why (PlanReport::left)

  // The patches of material the level left: what the passes did not reach in the level's map (the holder kept
  // them off, or no pass got there at the limit), and the material no cutter centre out of the part reaches.
  void report_left(const LevelRegions& r) {
    const double least = 0.05 * R_ * R_;  // the skin the chords leave on a curved wall, a cell or two wide
    for (const std::vector<size_t>& patch : material_.islands_off_walls(2)) {
      const double area = double(patch.size()) * cell_ * cell_;
      if (area < least) continue;
      Vec2 sum = Vec2::Zero();
      for (size_t c : patch) sum += material_.centre(c);
      const Vec2 c = sum / double(patch.size());
      add_left(area, c, held_off_by_the_body(c) ? UnclearedReason::kHolder : UnclearedReason::kEngagement);
    }
    report_unreached(r);
  }

  // Whether some centre within R of p keeps the cutter out of the part but the shank or holder there would meet
  // the material above, and none the body lets through does.
  bool held_off_by_the_body(const Vec2& p) const {
    if (!guard_.any()) return false;
    bool blocked = false;
    for (double d : {0.0, 0.5 * R_, 0.9 * R_})
      for (int k = 0; k < (d > 0 ? 16 : 1); ++k) {
        const Vec2 q = p + d * Vec2(std::cos(k * M_PI / 8), std::sin(k * M_PI / 8));
        if (!allowed_lookup_.contains(q)) continue;
        if (!guard_.blocked(q)) return false;
        blocked = true;
      }
    return blocked;
  }

  // The material standing where no cutter centre out of the part reaches (beyond R of every allowed centre) and
  // the part does not stand within the allowance: a gap narrower than the tool, an inner corner tighter than its
  // radius. Sought on points R / 10 apart, each asked of the surface with a cutter of the allowance: from those
  // within 2 R of the allowed centres (a corner's material lies within R (sqrt 2 - 1) of them, a gap's mouth
  // within R) along the gaps as far as they go, grouped into patches across the grid's edges.
  void report_unreached(const LevelRegions& r) {
    const clip::Paths unreached = clip::subtract(r.material, clip::offset(r.allowed, R_, arc_));
    const clip::Paths band = clip::intersect(unreached, clip::offset(r.allowed, 2 * R_, arc_));
    if (clip::area(band) < 1e-3 * R_ * R_) return;
    const double s = 0.1 * R_;
    Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
    for (const clip::Path& path : unreached)
      for (const auto& q : path) {
        const Vec2 v = clip::from_point(q);
        lo = Vec2(std::min(lo.x(), v.x()), std::min(lo.y(), v.y()));
        hi = Vec2(std::max(hi.x(), v.x()), std::max(hi.y(), v.y()));
      }
    const long nx = long(std::ceil((hi.x() - lo.x()) / s)), ny = long(std::ceil((hi.y() - lo.y()) / s));
    const RegionLookup in_band(band, std::max(s, 4 * cell_)), in_unreached(unreached, std::max(s, 4 * cell_));
    const Cutter probe = Cutter::flat(2 * std::max(f_.allowance + f_.tolerance, 0.01));
    const auto at = [&](long i, long j) -> Vec2 { return lo + Vec2((i + 0.5) * s, (j + 0.5) * s); };
    const auto left_at = [&](const Vec2& p) { return !surface_->held_above(probe, p.x(), p.y(), z_); };
    // 0 not asked, 1 material left, 2 left and grouped, 3 none.
    std::vector<uint8_t> state(size_t(nx) * size_t(ny), 0);
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i) {
        const size_t c = size_t(j * nx + i);
        if (state[c] != 0) continue;
        const Vec2 p = at(i, j);
        if (!in_band.contains(p)) continue;
        if (!left_at(p)) {
          state[c] = 3;
          continue;
        }
        std::vector<size_t> open{c};
        state[c] = 2;
        size_t n = 0;
        Vec2 sum = Vec2::Zero();
        while (!open.empty()) {
          const size_t k = open.back();
          open.pop_back();
          const long kj = long(k) / nx, ki = long(k) % nx;
          ++n, sum += at(ki, kj);
          for (const auto& [di, dj] : {std::pair{1L, 0L}, {-1L, 0L}, {0L, 1L}, {0L, -1L}}) {
            if (ki + di < 0 || kj + dj < 0 || ki + di >= nx || kj + dj >= ny) continue;
            const size_t m = size_t((kj + dj) * nx + ki + di);
            if (state[m] != 0) continue;
            const Vec2 q = at(ki + di, kj + dj);
            state[m] = in_unreached.contains(q) && left_at(q) ? 2 : 3;
            if (state[m] == 2) open.push_back(m);
          }
        }
        if (double(n) * s * s >= 0.05 * R_ * R_) add_left(double(n) * s * s, sum / double(n), UnclearedReason::kNarrowerThanTheTool);
      }
  }

  void add_left(double area, const Vec2& p, UnclearedReason reason) {
    UnclearedPatch l;
    l.z = z_, l.area_mm2 = area, l.x = p.x(), l.y = p.y(), l.reason = reason;
    report_.uncleared.push_back(l);
  }

  // ---- steered passes

  // One pass: from the start in air, the cutter turns toward the material and then runs with it on its right
  // (climb milling for an M3 spindle), each step turned as far into the material as keeps the engagement at the
  // target, until no turn within the turn radius keeps it under the limit out of the part, or it has run a
  // while in air. So the path follows the boundary of the cleared area at a constant engagement: a spiral in open
  // material, an arc across the front of a channel, slowed into inner corners by turning away from them.
  void pass(const Start& start) {
    begin_attempt();
    reach_air(start.p, start.h);
    Vec2 p = start.p, h = start.h;
    double air = 0, air_turn = 0;
    int cut = 0;  // steps that cut
    std::vector<Vec2> in_air;  // steps through air not yet taken: dropped if the pass ends in air
    Step last;
    while (steps_ < kMaxSteps) {
      ++steps_;
      const std::optional<Step> next = steer(p, h, 1, last);
      if (!next) break;
      last = *next;
      // Air where the step would cut no cell (the engagement may still see the cells a disc's edge leaves, their
      // centres just beyond R).
      // (The material it would cut is kept, to be cut without a second search when the step is taken.)
      const bool air_step = !material_.material_ahead(p, next->p, R_, ahead_);
      const double turn = std::atan2(h.x() * next->h.y() - h.y() * next->h.x(), h.dot(next->h));
      p = next->p, h = next->h;
      if (air_step) {
        // Round a convex corner of the material through air, but no loop: a pass that has turned through more
        // than kAirTurn or run 2 R in air since it last cut ends there.
        air += step_;
        air_turn += turn;
        if (air > 2 * R_ || std::abs(air_turn) > kAirTurn) break;
        in_air.push_back(p);
        continue;
      }
      air_turn = 0;
      for (const Vec2& q : in_air) cut_to(q);  // through air: they cut nothing, ahead_ stays what p cuts
      in_air.clear();
      cut_to(p, &ahead_);
      air = 0;
      ++cut;
    }
    // A pass that cuts for fewer than min_steps_ steps and less than R x step of area is not made: it is one of the
    // small loops that jerk a machine for next to no material; its start is given up and what it would take is left
    // to later passes, the wall pass, or reported as left. (A small island is still taken: its area counts.)
    if (cut < min_steps_ && double(attempt_.cut_cells.size()) * cell_ * cell_ < R_ * step_) {
      undo_attempt();
      given_up_[start.cell] = 1;
      give_up_near(start.p, R_ + step_);
      return;
    }
    commit_attempt();
    last_start_ = start.p;
    ++report_.passes;
    if (cut < kMinPassSteps) ++report_.short_passes;
  }

  // ---- a pass tried before it is written: its link and moves are kept, the cells it cuts logged, the links'
  // heights lowered only once it is made.

  struct Attempt {
    bool active = false;
    Vec2 at = Vec2::Zero();           // where the cutter would be
    std::optional<Vec2> descent;      // a lift and descent to here first
    std::vector<Vec2> moves;          // feed moves along the level
    std::vector<double> engagement;   // of each
    size_t corner_links = 0;          // links among them that turn on the spot
    size_t air_links = 0;             // links among them round what stands between, through cleared air
    Vec2 heading = Vec2::UnitX();     // the cutter's heading before the attempt
    std::vector<size_t> cut_cells;    // the material cells it cut, to restore
  };

  void begin_attempt() {
    attempt_.active = true;
    attempt_.at = w_->position().head<2>();
    attempt_.descent.reset();
    attempt_.moves.clear();
    attempt_.engagement.clear();
    attempt_.corner_links = 0;
    attempt_.air_links = 0;
    attempt_.heading = heading_;
    attempt_.cut_cells.clear();
    material_.log_cuts(&attempt_.cut_cells);
  }

  void undo_attempt() {
    material_.log_cuts(nullptr);
    material_.restore(attempt_.cut_cells);
    heading_ = attempt_.heading;
    attempt_.active = false;
  }

  void commit_attempt() {
    material_.log_cuts(nullptr);
    attempt_.active = false;
    if (attempt_.descent) descend(*attempt_.descent);
    report_.corner_links += attempt_.corner_links;
    report_.air_links += attempt_.air_links;
    for (size_t k = 0; k < attempt_.moves.size(); ++k) write_feed(attempt_.moves[k], attempt_.engagement[k]);
  }

  // Where the cutter is, or would be in the pass being tried.
  Vec2 position() const { return attempt_.active ? attempt_.at : Vec2(w_->position().head<2>()); }
  bool at_level_now() const { return (attempt_.active && attempt_.descent) || at_level(); }

  // The level's last pass: round the walls (the allowed region opened by the turn radius, climb) wherever
  // material is left within reach of them: the corners and the strips the passes left as they turned away from
  // the walls within their turn radius. Each stretch that cuts, widened by a radius of air either side, is
  // entered from air.
  void wall_pass() {
    // A slot goes to any engagement (up to the whole diameter), only where the centres have no room for the turn
    // radius (a channel narrower than the tool and two turn radii: the opened region leaves it out; a corner's
    // rounding, under half a turn radius deep, is not such a place), along the allowed region's own boundary.
    const double most = slotting_ ? 181.0 : target_;
    const clip::Paths opened = clip::open(allowed_, r_min_, arc_);
    RegionLookup narrow;
    if (slotting_) {
      const clip::Paths cramped = clip::subtract(allowed_, clip::offset(opened, 0.5 * r_min_, arc_));
      if (clip::area(cramped) < 1e-3 * R_ * R_) return;
      narrow = RegionLookup(cramped, 4 * cell_);
    }
    for (const clip::Path& path : slotting_ ? allowed_ : opened) {
      std::vector<Vec2> p;
      std::vector<uint8_t> corner;
      const size_t m = path.size();
      for (size_t k = 0; k < m; ++k) {
        const Vec2 a = clip::from_point(path[k]), b = clip::from_point(path[(k + 1) % m]);
        const int parts = std::max(1, static_cast<int>(std::ceil((b - a).norm() / cell_)));
        for (int i = 0; i < parts; ++i) p.push_back(a + (b - a) * (double(i) / parts)), corner.push_back(i == 0);
      }
      const size_t n = p.size();
      if (n < 3) continue;
      std::vector<uint8_t> keep(n, 0);
      const size_t pad = static_cast<size_t>(std::ceil(R_ / cell_));
      for (size_t k = 0; k < n; ++k) {
        const Vec2 dir = (p[(k + 1) % n] - p[k]).normalized();
        if ((!slotting_ || narrow.contains(p[k])) && material_.engagement(p[k], dir, R_ - cell_) > kAirDeg)
          for (size_t d = 0; d <= 2 * pad; ++d) keep[(k + n + d - pad) % n] = 1;
      }
      if (std::none_of(keep.begin(), keep.end(), [](uint8_t b) { return b; })) continue;
      // Stretches of kept samples, from one after a dropped sample (a loop kept whole starts anywhere).
      size_t first = 0;
      while (first < n && keep[first]) ++first;
      first = first == n ? 0 : first;
      for (size_t k = 0; k < n;) {
        const size_t i = (first + k) % n;
        if (!keep[i]) {
          ++k;
          continue;
        }
        size_t len = 0;
        while (k + len < n && keep[(first + k + len) % n]) ++len;
        if (material_.disc_clear(p[i], R_) && in_part_clearance(p[i])) {
          // Up to where the engagement would pass the target (a corner the passes left thick): the rest stays.
          size_t end = 1;
          for (; end <= len; ++end) {
            const size_t at = (i + end) % n;
            if (!in_part_clearance(p[at]) ||
                material_.engagement(p[at], (p[at] - p[(at + n - 1) % n]).normalized(), R_) > most)
              break;
          }
          if (end > 1) reach_air(p[i], (p[(i + 1) % n] - p[i]).normalized());
          for (size_t j = 1; j < end; ++j) {
            const size_t at = (i + j) % n;
            if (corner[at] || j + 1 == end) cut_to(p[at]);
          }
        }
        k += len;
      }
    }
  }

  // The pins the passes left off the walls: islands of material too small for a pass of their own (a pass that
  // would cut less than R x step is not made), which a roughed face would keep as spikes a step-down high. Each,
  // nearest first, is taken by a short straight move into it from the cleared air beside it, that air reached
  // as a pass's start is.
  void take_pins() {
    std::vector<std::vector<size_t>> pins = material_.islands_off_walls(2);
    std::vector<Vec2> centres;
    for (const std::vector<size_t>& pin : pins) {
      Vec2 sum = Vec2::Zero();
      for (size_t c : pin) sum += material_.centre(c);
      centres.push_back(sum / double(pin.size()));
    }
    while (!pins.empty()) {
      const Vec2 from = position();
      size_t next = 0;
      for (size_t k = 1; k < pins.size(); ++k)
        if ((centres[k] - from).squaredNorm() < (centres[next] - from).squaredNorm()) next = k;
      take_pin(pins[next], centres[next]);
      pins.erase(pins.begin() + long(next));
      centres.erase(centres.begin() + long(next));
    }
  }

  // A pin whose cells lie within half a radius of c: from the first of eight sides whose way to c keeps out of the
  // part and cuts at the target engagement at most.
  void take_pin(const std::vector<size_t>& pin, const Vec2& c) {
    double reach = 0;
    for (size_t k : pin) reach = std::max(reach, (material_.centre(k) - c).norm());
    if (reach > 0.5 * R_ || !in_part_clearance(c)) return;  // not a pin: left, and reported as left
    for (int d = 0; d < 8; ++d) {
      const Vec2 u(std::cos(d * M_PI / 4), std::sin(d * M_PI / 4));
      const Vec2 side = c - (R_ + reach + 2 * cell_) * u;
      if (!in_part_clearance(side) || !material_.disc_clear(side, R_) || !free_curve(side, {c})) continue;
      reach_air(side, u);
      cut_to(c);
      return;
    }
  }

  // The next step from p along h, the material on the right (sign 1), or walking back along the front a pass
  // would cut, the material on the left (sign -1). The heading turns by at most max_turn_, to one of kTurns + 1
  // turns evenly spaced from fully away from the material (0) to fully into it (kTurns): the farthest into the
  // material that stays out of the part with room to turn away from its wall and whose engagement stays at the
  // target (the engagement grows as the turn goes into the material). None when even the turn farthest from the
  // material is over the target or no turn keeps out of the part. `last` is the step before (a default Step at a
  // path's start): when its way out was open (Step::escapes), the turn fully away is known under the target
  // without measuring it; its turn is where the searches begin.
  std::optional<Step> steer(const Vec2& p, const Vec2& h, int sign, const Step& last) const {
    const double into = -sign * max_turn_;  // toward the material: right of a cut, left walking back
    const auto turn_of = [&](int k) { return into * (2.0 * k / kTurns - 1); };
    const auto placed = [&](double a) {
      Step s;
      s.h = turned(h, a);
      s.p = p + step_ * s.h;
      return s;
    };
    // Turn k of the grid: turns_[k] with the material on the right, mirrored with it on the left.
    const auto turned_to = [&](const Vec2& g, int k) {
      return turned_by(g, Vec2(turns_[k].x(), sign * turns_[k].y()));
    };
    // Over the target at the end of the step (the cut runs along sign * h).
    const auto over = [&](const Step& s) { return material_.engaged_over(s.p, sign * s.h, R_, target_); };
    // Under the target at the samples along the step before its end too: a turn under it at the end can still pass
    // it on the way (a sliver met head-on). Tried on the turn the end's search found, and searched again when it
    // fails: most steps pass.
    const int n = samples(step_);
    const auto along_ok = [&](const Step& s) {
      for (int k = 1; k < n; ++k)
        if (material_.engaged_over(p + (step_ * k / n) * s.h, sign * s.h, R_, target_)) return false;
      return true;
    };
    // Room ahead to turn away from a wall within the turn radius (and so to link to the next pass by a curve).
    const auto clear = [&](const Step& s) {
      return in_part_clearance(s.p) && in_part_clearance(s.p + kWallRoom * r_min_ * s.h);
    };
    // A step leaves a way out: turning away as fast as the turn radius allows for kEscapeSteps more steps keeps
    // the engagement at the target. Without it a pass that meets a front from air (nothing to steer by, so it
    // turns fully into the material) or runs into a concave bay of it is turned into the material faster than it
    // can turn back, and ends a few steps in, its start given up: many short passes linked by loops through air.
    const auto escapes = [&](const Step& s) {
      Vec2 q = s.p, g = s.h;
      for (int k = 0; k < kEscapeSteps; ++k) {
        g = turned_to(g, 0), q += step_ * g;
        if (material_.engaged_over(q, sign * g, R_, target_)) return false;
      }
      return true;
    };
    // The grid's turns, each placed and measured once whichever search asks.
    enum : uint8_t { kPlaced = 1, kEnd = 2, kAlongKnown = 4, kAlongUnder = 8, kRoomKnown = 16, kRoom = 32 };
    std::array<Step, kTurns + 1>& grid = grid_;
    std::array<uint8_t, kTurns + 1> known{};
    const auto place = [&](int k) -> Step& {
      if (!(known[k] & kPlaced)) {
        grid[k].h = turned_to(h, k), grid[k].p = p + step_ * grid[k].h;
        grid[k].over = grid[k].escapes = false, known[k] |= kPlaced;
      }
      return grid[k];
    };
    const auto end_under = [&](int k) {
      Step& s = place(k);
      if (!(known[k] & kEnd)) s.over = over(s), known[k] |= kEnd;
      return !s.over;
    };
    const auto under = [&](int k) {
      if (!end_under(k)) return false;
      if (!(known[k] & kAlongKnown)) known[k] |= kAlongKnown | (along_ok(grid[k]) ? kAlongUnder : 0);
      return (known[k] & kAlongUnder) != 0;
    };
    const auto roomy = [&](int k) {
      if (!(known[k] & kRoomKnown)) known[k] |= kRoomKnown | (clear(place(k)) ? kRoom : 0);
      return (known[k] & kRoom) != 0;
    };
    // The turn fully away is the fallback of every search below: it is taken to pass, so it is checked first. Its
    // samples along the step are measured only when a search may fall back on it.
    if (last.escapes) {
      place(0);
      known[0] |= kEnd;
    } else if (!end_under(0)) {
      return std::nullopt;
    }
    // The farthest turn into the material with room, first: a lookup where the engagement is a measure of the
    // material, and along a wall (most steps of a narrow region) the bound the engagement's search stays within.
    const int room = roomy(kTurns) ? kTurns : last_passing(0, kTurns, last.turn, roomy);
    // The farthest turn under the target at its end, then along the step; when the way out from there is closed,
    // the farthest that keeps it open (tried only then: a pass along a front nearly always has one).
    int k = last_passing(0, room + 1, last.turn, end_under);
    if (!under(k)) {
      if (!under(0)) return std::nullopt;
      k = last_passing(0, k, k - 1, under);
    }
    Step best = grid[k];
    best.turn = k;
    best.escapes = escapes(best);
    if (!best.escapes && escapes(grid[0]) && under(0)) {
      k = last_passing(0, k, k - 1, [&](int j) { return under(j) && escapes(grid[j]); });
      best = grid[k];
      best.turn = k;
      best.escapes = true;  // every turn the search keeps passed escapes(), the turn fully away too
    }
    if (roomy(k)) return best;
    // No room there (where room is not a single span of turns): back toward the turn fully away.
    const double a_ok = turn_of(k);
    for (int j = 1; j <= 8; ++j) {
      Step s = placed(a_ok + (-into - a_ok) * j / 8.0);
      if (!clear(s)) continue;
      s.over = over(s);
      if (!s.over && along_ok(s)) return s.turn = k, s;
    }
    return std::nullopt;
  }

  // Where the next pass begins: at the edge of the material nearest where the last pass began (blocks searched
  // outward from there), the cutter placed in air beside it. A pass that ran across a front from one wall to
  // the other began at the front's upstream end, so the next takes the whole front again a step further on
  // rather than the stub at the wall where the last ended (a trochoidal advance along a channel).
  std::optional<Start> next_start() {
    const Vec2 from = at_level() ? last_start_ : w_->position().head<2>();
    long bi = 0, bj = 0;
    material_.block_of(from, bi, bj);
    const long rings = std::max({bi, bj, material_.blocks_x() - bi, material_.blocks_y() - bj});
    std::vector<std::pair<double, size_t>> edge;
    std::vector<Vec2> normal;
    size_t sorted = 0;  // edge[0, sorted) is in order
    for (long ring = 0; ring <= rings; ++ring) {
      // The ring's blocks row by row from the bottom, each row from the left: its bottom and top rows whole, the
      // rows between at its two sides only.
      for (long j = bj - ring; j <= bj + ring; ++j) {
        const long step = j == bj - ring || j == bj + ring ? 1 : 2 * ring;
        for (long i = bi - ring; i <= bi + ring; i += step)
          material_.edge_cells(i, j, [&](size_t c) { return given_up_[c] != 0; },
                                [&](size_t c, const Vec2& centre, const Vec2& n) {
            edge.push_back({(centre - from).squaredNorm(), normal.size()});
            normal.push_back(n);
            cells_.push_back(c);
          });
      }
      // Every cell nearer than this ring's inner side is in: try them nearest first.
      const double sure = std::max(0.0, (ring - 1) * material_.block_span());
      // The ring's cells sorted and merged into those left from the rings before (the same order as sorting all).
      std::sort(edge.begin() + long(sorted), edge.end());
      std::inplace_merge(edge.begin(), edge.begin() + long(sorted), edge.end());
      size_t tried = 0;
      for (; tried < edge.size() && (edge[tried].first <= sure * sure || ring == rings); ++tried) {
        const size_t k = edge[tried].second;
        const std::optional<Start> s = start_at(cells_[k], normal[k]);
        if (s) {
          cells_.clear();
          return s;
        }
        given_up_[cells_[k]] = 1;
      }
      edge.erase(edge.begin(), edge.begin() + tried);
      sorted = edge.size();
    }
    cells_.clear();
    return std::nullopt;
  }

  // A start beside edge cell c whose air lies along n: the cutter's disc clear of material and out of the part,
  // a cell off the edge; then the walk back along the front.
  std::optional<Start> start_at(size_t c, const Vec2& n) {
    const Vec2 m = material_.centre(c);
    for (double turn : {0.0, 0.5, -0.5}) {
      const Vec2 u = turned(n, turn);
      const Vec2 p = m + (R_ + 2 * cell_) * u;
      const Vec2 h = turned(Vec2(u.y(), -u.x()), -lead_in_);
      if (!in_part_clearance(p) || !material_.disc_clear(p, R_) || material_.engagement(p, h, R_) > 0) continue;
      return walk_back(Start{p, h, c});
    }
    return std::nullopt;
  }

  // No pass starts at the skin of material on the walls (within two cells of the cells beyond the target): a pass
  // along a wall leaves it where its chords fall inside the wall's curve, and chasing it would make passes that
  // cut nearly nothing. The wall pass takes what of it a cutter reaches.
  void give_up_skin() {
    const long nx = material_.nx(), ny = material_.ny();
    const size_t width = static_cast<size_t>(nx);
    // Of each row, per cell: bit 0 it is the part's (kOther), bit 1 one of the three cells centred on it is, bit 2
    // one of the five. The window (the 3 x 3 square and the four cells two away along the axes) is then bit 2 of
    // the cell's row, bit 1 of the rows beside it and bit 0 of the rows two away. Loops without branches over
    // whole rows, through plain pointers (byte stores may alias anything else): vectorised.
    std::vector<uint8_t> part_row(width + 4, 0), three_row(width + 2, 0);  // [i + 2], [i + 1]: cell i
    const auto part_near = [&](long j, std::vector<uint8_t>& near) {
      near.assign(width, 0);
      if (j < 0 || j >= ny) return;
      const uint8_t* const cells = material_.values() + size_t(j) * width;
      uint8_t* const part = part_row.data();
      uint8_t* const three = three_row.data();
      uint8_t* const out = near.data();
      for (size_t i = 0; i < width; ++i) part[i + 2] = cells[i] == LevelMaterial::kOther;
      for (size_t i = 0; i < width; ++i) three[i + 1] = part[i + 1] | part[i + 2] | part[i + 3];
      for (size_t i = 0; i < width; ++i)
        out[i] = uint8_t((three[i] | three[i + 1] | three[i + 2]) << 2 | three[i + 1] << 1 | part[i + 2]);
    };
    std::array<std::vector<uint8_t>, 5> rows;  // rows j - 2 ... j + 2
    for (long k = 0; k < 4; ++k) part_near(k - 2, rows[size_t(k) + 1]);
    for (long j = 0; j < ny; ++j) {
      std::rotate(rows.begin(), rows.begin() + 1, rows.end());
      part_near(j + 2, rows[4]);
      const uint8_t* const cells = material_.values() + size_t(j) * width;
      uint8_t* const given_up = given_up_.data() + size_t(j) * width;
      const uint8_t *const r0 = rows[0].data(), *const r1 = rows[1].data(), *const r2 = rows[2].data(),
                          *const r3 = rows[3].data(), *const r4 = rows[4].data();
      for (size_t i = 0; i < width; ++i) {
        const uint8_t near = (r2[i] >> 2 | (r1[i] | r3[i]) >> 1 | r0[i] | r4[i]) & 1;
        given_up[i] |= uint8_t(cells[i] == LevelMaterial::kMaterial) & near;
      }
    }
  }

  // From s back along the front the pass would cut (up to kWalkBack radii), past a corner onto the strip of
  // material a wall keeps, to where the front begins: a wall, air, or a turn over the limit. Then out into air beside
  // it on the cut's left (the cleared side), heading lead_in_ into the material. So a pass runs the whole front
  // from where it begins (along a wall's strip, into the corner, down the front) rather than from the middle of it,
  // which would leave the strip to small passes.
  Start walk_back(const Start& s) const {
    Vec2 p = s.p, h = -turned(s.h, lead_in_);
    bool met = false;  // the walk sets off in air beside the front
    Step last;
    for (double walked = 0; walked < kWalkBack * R_; walked += step_) {
      const std::optional<Step> next = steer(p, h, -1, last);
      if (!next) break;
      last = *next;
      const bool air = material_.engagement(next->p, -next->h, R_ - cell_) < kAirDeg;
      if (air && (met || walked > 2 * R_)) break;
      met = met || !air;
      p = next->p, h = next->h;
    }
    if (!met) return s;
    const Vec2 cut = -h, left(-cut.y(), cut.x());
    for (double off = cell_; off <= R_ + 2 * cell_; off += cell_) {
      const Vec2 q = p + off * left;
      if (!in_part_clearance(q)) break;
      if (material_.disc_clear(q, R_) && material_.engagement(q, turned(cut, -lead_in_), R_) == 0)
        return {q, turned(cut, -lead_in_), s.cell};
    }
    return s;
  }

  // Material cells within r of p are no longer tried as the start of a pass.
  void give_up_near(const Vec2& p, double r) {
    const double c = material_.cell();
    for (double y = p.y() - r; y <= p.y() + r; y += c)
      for (double x = p.x() - r; x <= p.x() + r; x += c) {
        const size_t k = cell_index(Vec2(x, y));
        if (k != kNoCell && (Vec2(x, y) - p).norm() <= r) given_up_[k] = 1;
      }
  }

  static constexpr size_t kNoCell = size_t(-1);
  size_t cell_index(const Vec2& p) const {
    const Vec2 o = material_.centre(0) - Vec2::Constant(0.5 * cell_);
    const long i = static_cast<long>(std::floor((p.x() - o.x()) / cell_));
    const long j = static_cast<long>(std::floor((p.y() - o.y()) / cell_));
    if (i < 0 || j < 0 || i >= material_.nx() || j >= material_.ny()) return kNoCell;
    return size_t(j) * material_.nx() + i;
  }

  // ---- links

  // To p, whose disc is clear, arriving along h: along the level by the shortest curve of the turn radius that
  // meets no material and stays out of the part (a Dubins path, geometry/dubins.hpp; a straight line when the
  // turn radius is 0), else from above.
  void reach_air(const Vec2& p, const Vec2& h) {
    if (at_level_now()) {
      const Vec2 from = position();
      if (r_min_ <= 0) {
        if (free_way(from, p)) return cut_to(p);
      } else if ((p - from).norm() > 1e-9 || (h - heading_).norm() > 1e-9) {
        // The curve ends a step short, on a straight move along h: the pass's first step then turns from a move
        // as long as itself, no sharper than the rest.
        const Vec2 q = p - step_ * h;
        for (const DubinsPath& path : dubins_paths(from, heading_, q, h, r_min_)) {
          if (path.length() > 8 * R_) break;
          std::vector<Vec2> way = dubins_points(path, from, heading_, step_);
          way.push_back(p);
          if (!free_curve(from, way)) continue;
          for (const Vec2& w : way) cut_to(w);
          return;
        }
        // No curve of the turn radius fits the cleared air: a straight link, turning on the spot at its ends,
        // rather than a lift.
        if (free_way(from, p)) {
          ++(attempt_.active ? attempt_.corner_links : report_.corner_links);
          return cut_to(p);
        }
        // Round what stands between, through the air cleared at the level, rather than a lift.
        if (const std::optional<std::vector<Vec2>> way = air_route(from, p)) {
          // Each of its straight pieces turns on the spot at its ends: a corner link of its own.
          ++(attempt_.active ? attempt_.air_links : report_.air_links);
          (attempt_.active ? attempt_.corner_links : report_.corner_links) += way->size();
          for (const Vec2& w : *way) cut_to(w);
          return;
        }
      } else {
        return;
      }
    }
    if (attempt_.active) {
      attempt_.descent = p;
      attempt_.at = p;
      return;
    }
    descend(p);
  }

  // A way along the level from a to b through air (the cutter's disc clear of material, its centre out of the
  // part and the fixture) that no straight link or curve finds: a breadth-first search over cells of about R / 8
  // whose centres stand more than R and a cell's diagonal from the material (a 3-4 chamfer distance, as seed_on's),
  // within 6 R of the two ends' box, then pulled taut: each point one of the search's way seen straight from the
  // one before, as far on as a doubling search finds. None when the search finds no way.
  std::optional<std::vector<Vec2>> air_route(const Vec2& a, const Vec2& b) {
    const long f = coarse_cells();
    const double c = f * cell_;
    const long nx = material_.nx(), ny = material_.ny();
    const Vec2 o = material_.centre(0) - Vec2::Constant(0.5 * cell_);
    const auto fine = [&](double v, double o0, long n) {
      return std::clamp(static_cast<long>(std::floor((v - o0) / cell_)), 0L, n - 1);
    };
    const double grow = 6 * R_;
    const long i0 = fine(std::min(a.x(), b.x()) - grow, o.x(), nx) / f * f;
    const long j0 = fine(std::min(a.y(), b.y()) - grow, o.y(), ny) / f * f;
    const long i1 = fine(std::max(a.x(), b.x()) + grow, o.x(), nx), j1 = fine(std::max(a.y(), b.y()) + grow, o.y(), ny);
    const long wx = (i1 - i0) / f + 1, wy = (j1 - j0) / f + 1;
    std::vector<float>& to_material = scratch_[0];
    to_material.assign(size_t(wx) * wy, INFINITY);
    const uint8_t* const cells = material_.values();
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i)
        if (cells[size_t(j) * nx + i] == LevelMaterial::kMaterial) to_material[size_t((j - j0) / f) * wx + (i - i0) / f] = 0;
    chamfer(to_material, wx, wy, c);
    const Vec2 corner = o + Vec2(i0 * cell_, j0 * cell_);
    const auto centre = [&](long w) -> Vec2 { return corner + Vec2((w % wx + 0.5) * c, (w / wx + 0.5) * c); };
    const float room = static_cast<float>(R_ + 1.5 * c);
    std::vector<long>& came = route_came_;  // -2 unseen, -1 a start, else the cell it was reached from
    came.assign(size_t(wx) * wy, -2);
    std::vector<long>& open = route_open_;
    open.clear();
    const auto free = [&](long w) { return to_material[size_t(w)] > room && in_part_clearance(centre(w)); };
    const auto cell_of = [&](const Vec2& p) {
      const long i = std::clamp(static_cast<long>(std::floor((p.x() - corner.x()) / c)), 0L, wx - 1);
      const long j = std::clamp(static_cast<long>(std::floor((p.y() - corner.y()) / c)), 0L, wy - 1);
      return j * wx + i;
    };
    // The search begins at the cells beside a that a straight way from a reaches, ends at one that reaches b.
    const auto near = [&](const Vec2& p, const auto& each) {
      const long w = cell_of(p), i = w % wx, j = w / wx;
      for (long dj = -3; dj <= 3; ++dj)
        for (long di = -3; di <= 3; ++di)
          if (i + di >= 0 && j + dj >= 0 && i + di < wx && j + dj < wy) each((j + dj) * wx + i + di);
    };
    near(a, [&](long w) {
      if (came[size_t(w)] == -2 && free(w) && straight_in_air(a, centre(w))) came[size_t(w)] = -1, open.push_back(w);
    });
    std::vector<uint8_t>& goal = route_goal_;
    goal.assign(size_t(wx) * wy, 0);
    near(b, [&](long w) { goal[size_t(w)] = 1; });
    long end = -1;
    for (size_t k = 0; k < open.size() && end < 0; ++k) {
      const long w = open[k], i = w % wx, j = w / wx;
      if (goal[size_t(w)] && straight_in_air(centre(w), b)) end = w;
      for (long dj = -1; dj <= 1 && end < 0; ++dj)
        for (long di = -1; di <= 1; ++di) {
          if ((di == 0 && dj == 0) || i + di < 0 || j + dj < 0 || i + di >= wx || j + dj >= wy) continue;
          const long m = (j + dj) * wx + i + di;
          if (came[size_t(m)] != -2 || !free(m)) continue;
          came[size_t(m)] = w;
          open.push_back(m);
        }
    }
    if (end < 0) return std::nullopt;
    std::vector<Vec2> way{b};
    for (long w = end; w >= 0; w = came[size_t(w)]) way.push_back(centre(w));
    way.push_back(a);
    std::reverse(way.begin(), way.end());
    // Pulled taut from a: the farthest point seen straight from the last kept.
    std::vector<Vec2> taut;
    for (size_t k = 0; k + 1 < way.size();) {
      // Neighbouring cells of the search see each other; the farthest seen is sought by doubling strides, then
      // halving (last_passing): a few long checks rather than one per cell.
      const int last = int(way.size() - 1 - k);
      const int next = int(k) + last_passing(1, last + 1, 2, [&](int d) { return straight_in_air(way[k], way[k + size_t(d)]); });
      taut.push_back(way[size_t(next)]);
      k = size_t(next);
    }
    return taut;
  }

  // A straight way at the level whose cutter meets no material and whose centre keeps out of the part, any length.
  bool straight_in_air(const Vec2& a, const Vec2& b) const {
    if (!material_.capsule_clear(a, b, R_)) return false;
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / (0.5 * cell_))));
    for (int k = 0; k <= n; ++k)
      if (!in_part_clearance(a + (b - a) * (double(k) / n))) return false;
    return true;
  }

  // Every chord of the way from `from` keeps out of the part and cuts at most at the target engagement (it sets
  // off from the material the last pass ended against).
  bool free_curve(const Vec2& from, const std::vector<Vec2>& way) const {
    Vec2 a = from;
    for (const Vec2& b : way) {
      const double len = (b - a).norm();
      if (len < 1e-12) continue;
      const Vec2 dir = (b - a) / len;
      const int n = samples(len);
      for (int k = 1; k <= n; ++k) {
        const Vec2 q = a + (b - a) * (double(k) / n);
        if (!in_part_clearance(q) || material_.engaged_over(q, dir, R_, target_)) return false;
      }
      a = b;
    }
    return true;
  }

  bool at_level() const { return !w_->at_safe() && std::abs(w_->position().z() - z_) < 1e-9; }

  // A straight way along the level on which the cutter meets no material and stays out of the part.
  bool free_way(const Vec2& a, const Vec2& b) const {
    const double len = (b - a).norm();
    if (len > 8 * R_ || !material_.capsule_clear(a, b, R_)) return false;
    const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5 * cell_))));
    for (int k = 0; k <= n; ++k)
      if (!in_part_clearance(a + (b - a) * (double(k) / n))) return false;
    return true;
  }

  // p keeps the cutter out of the part (on the boundary too: a ring runs along the wall).
  // The tool's bodies above the cutter keep off the material left too (body_guard.hpp).
  bool in_part_clearance(const Vec2& p) const { return allowed_lookup_.contains(p) && !guard_.blocked(p); }

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
  }

  // A feed move along the level to p: its engagement measured before it cuts, its feed from the engagement.
  // `ahead`: the material cells the move cuts when already found (LevelMaterial::material_ahead from here to p).
  void cut_to(const Vec2& p, const std::vector<size_t>* ahead = nullptr) {
    const Vec2 a = position();
    const double len = (p - a).norm();
    if (len < 1e-9) return;
    const Vec2 dir = (p - a) / len;
    double e = 0;
    const int n = samples(len);
    for (int k = 1; k <= n; ++k) e = std::max(e, material_.engagement(a + (p - a) * (double(k) / n), dir, R_));
    heading_ = dir;
    // The disc at a was cut when the cutter got there (a move, a helix or ramp, or a descent into air).
    if (ahead) material_.cut_cells(*ahead);
    else material_.cut_ahead(a, p, R_);
    if (attempt_.active) {
      attempt_.moves.push_back(p);
      attempt_.engagement.push_back(e);
      attempt_.at = p;
      return;
    }
    write_feed(p, e);
  }

  // The feed move to p written, at the feed of its engagement e; the links' heights lowered along it.
  void write_feed(const Vec2& p, double e) {
    const Vec2 a = w_->position().head<2>();
    w_->feed(Vec3(p.x(), p.y(), z_));
    if (slotting_ && e > limit_) slot_move((p - a).norm(), e);
    else engagement_of_move(e);
    top_.lower_along(a, p, R_, z_, [&](double d) { return profile_.height(d); });
  }

  // How many points a move of length len is measured at (evenly, its end the last): one a cell.
  int samples(double len) const { return std::max(1, static_cast<int>(std::ceil(len / cell_ - 1e-6))); }

  // The material map and the links' heights lowered where the cutter passed at the level.
  void cut(const Vec2& a, const Vec2& b, double radius = NAN) {
    const double r = std::isnan(radius) ? R_ : radius;
    material_.cut_along(a, b, r);
    top_.lower_along(a, b, r, z_, [&](double d) { return profile_.height(d); });
  }

  // A move of the slot pass over the limit: its feed from its engagement, counted apart from the passes'.
  void slot_move(double length, double e) {
    const double feed = feed_for(std::min(e, 180.0));
    tp_.passes.back().moves.back().feed = feed;
    if (report_.slot_length_mm == 0) report_.slot_feed = feed;
    report_.slot_length_mm += length;
    report_.slot_max_engagement_deg = std::max(report_.slot_max_engagement_deg, e);
    report_.slot_feed = std::min(report_.slot_feed, feed);
  }

  void engagement_of_move(double e) {
    report_.max_engagement_deg = std::max(report_.max_engagement_deg, e);
    tp_.passes.back().moves.back().feed = feed_for(e);
  }

  // Radial chip thinning (cutter/chip_thinning.hpp), capped by the machine.
  double feed_for(double e) const { return feed_for_engagement(params_.tool, e, params_.max_feed); }

  // ---- entries where no cleared air is in reach

  // A helix (or a ramp) into the material left where no pass can start. Its centre is where the region of
  // allowed centres within 0.9 R of that material is deepest (a chamfer distance over the cells, as far as the
  // helix radius). False when no material is left that an entry reaches.
  bool seed() {
    // Every entry searches the level's map: after kMaxFailedEntries entries that took next to nothing, what no pass
    // reaches is left (reported as left area) rather than searched again and again.
    if (failed_entries_ >= kMaxFailedEntries) return false;
    const std::vector<uint8_t>& closed = closed_material();
    // On cells of about R / 8 first (the depth need not be finer: the helix is checked point by point), then on
    // the map's own cells, where a slot barely wider than the tool has room for no coarse cell.
    const long coarse = coarse_cells();
    std::optional<bool> entered = seed_on(closed, coarse);
    if (!entered && coarse > 1) entered = seed_on(closed, 1);
    if (entered) return *entered;
    for (size_t c = 0; c < closed.size(); ++c)
      if (closed[c]) given_up_[c] = 1;
    return false;
  }

  long coarse_cells() const { return std::max(1L, static_cast<long>(std::floor(R_ / 8 / cell_))); }

  // seed() on cells of f x f of the map's: whether an entry was made (or a way in given up), none when no centre
  // has room.
  std::optional<bool> seed_on(const std::vector<uint8_t>& closed, long f) {
    // The window the entry is sought in: the closed material's box, grown by how far from it a centre may be.
    const long nx = material_.nx(), ny = material_.ny();
    // Row j's cells closed and not given up, into `wanted` (a loop without branches: vectorised); whether any is.
    std::vector<uint8_t> wanted(static_cast<size_t>(nx));
    const auto wanted_in = [&](long j) {
      const uint8_t* const closed_cells = closed.data() + size_t(j) * nx;
      const uint8_t* const given_up = given_up_.data() + size_t(j) * nx;
      uint8_t* const out = wanted.data();
      uint8_t any = 0;
      for (size_t i = 0; i < size_t(nx); ++i)
        any |= out[i] = uint8_t(closed_cells[i] != 0) & uint8_t(given_up[i] == 0);
      return any != 0;
    };
    long i0 = nx, i1 = -1, j0 = ny, j1 = -1;
    for (long j = 0; j < ny; ++j) {
      if (!wanted_in(j)) continue;
      const long first = std::find(wanted.begin(), wanted.end(), 1) - wanted.begin();
      const long last = wanted.rend() - std::find(wanted.rbegin(), wanted.rend(), 1) - 1;
      i0 = std::min(i0, first), i1 = std::max(i1, last), j0 = std::min(j0, j), j1 = std::max(j1, j);
    }
    if (i1 < 0) return false;
    const long grow = static_cast<long>(std::ceil(0.9 * R_ / cell_)) + 2 * f;
    i0 = std::max(0L, i0 - grow), j0 = std::max(0L, j0 - grow);
    i1 = std::min(nx - 1, i1 + grow), j1 = std::min(ny - 1, j1 + grow);
    const double cell = f * cell_;
    const long wx = (i1 - i0) / f + 1, wy = (j1 - j0) / f + 1;
    const size_t n = size_t(wx) * wy;
    std::vector<float>& to_material = scratch_[0];
    std::vector<float>& depth = scratch_[1];
    to_material.assign(n, INFINITY);
    depth.assign(n, 0);
    for (long j = j0; j <= j1; ++j) {
      if (!wanted_in(j)) continue;
      float* const window_row = &to_material[size_t((j - j0) / f) * wx];
      for (long w = 0; w < wx; ++w)  // window column w: cells i0 + w f ... of the row
        for (long i = i0 + w * f; i < std::min(i1 + 1, i0 + (w + 1) * f); ++i)
          if (wanted[size_t(i)]) window_row[w] = 0;
    }
    chamfer(to_material, wx, wy, cell);
    const float reach = static_cast<float>(0.9 * R_);
    const Vec2 corner = material_.centre(size_t(j0) * nx + size_t(i0)) - Vec2::Constant(0.5 * cell_);
    LevelMaterial& allowed = window_;
    allowed.reset(corner, corner + Vec2((wx - 0.5) * cell, (wy - 0.5) * cell), cell);  // wx x wy cells
    allowed.fill(allowed_, LevelMaterial::kMaterial);
    for (size_t w = 0; w < n; ++w)
      depth[w] = allowed.value(w) == LevelMaterial::kMaterial && to_material[w] <= reach &&
                         !guard_.blocked(allowed.centre(w))
                     ? INFINITY
                     : 0;
    chamfer(depth, wx, wy, cell);
    // The deepest cells (as deep as the helix needs), and of them the one nearest their centroid: the middle of
    // a slot, where a ramp reaches both ends.
    float deepest = 0;
    for (size_t w = 0; w < n; ++w) deepest = std::max(deepest, std::min<float>(depth[w], helix_));
    std::vector<size_t> deep;
    Vec2 sum = Vec2::Zero();
    for (size_t w = 0; w < n && deepest > 0; ++w)
      if (std::min<float>(depth[w], helix_) >= deepest) deep.push_back(w), sum += allowed.centre(w);
    size_t best = kNoCell;
    double nearest = INFINITY;
    for (size_t w : deep) {
      const double d = (allowed.centre(w) - sum / double(deep.size())).squaredNorm();
      if (d < nearest) nearest = d, best = w;
    }
    if (best == kNoCell) return std::nullopt;
    const Vec2 p = allowed.centre(best);
    const double room = std::max(0.0, double(depth[best]) - cell);
    const double before = material_.material_area();
    if (std::min(helix_, room) >= std::max(0.05 * R_, 2 * cell_) && helix_fits(p, std::min(helix_, room)))
      helix(p, std::min(helix_, room));
    else if (!ramp(p)) {
      give_up_near(p, 2 * R_);
      ++failed_entries_;
      return true;
    }
    // No entry twice at one place: where it took next to nothing, the material within reach of the centre (and of
    // the coarse cell it came from) is given up as a place to enter.
    if (material_.material_area() > before - 0.01 * R_ * R_) {
      give_up_near(p, 2 * R_);
      ++failed_entries_;
    }
    return true;
  }

  // The material no pass can start into: cells not joined (across edges) to any material that borders air. An
  // entry opens these; what borders air and was given up stays.
  const std::vector<uint8_t>& closed_material() {
    const long nx = material_.nx(), ny = material_.ny();
    const size_t n = size_t(nx) * ny;
    std::vector<uint8_t>& closed = closed_;
    closed.resize(n);  // every cell written below
    std::vector<size_t> open;
    const auto is = [&](long i, long j, uint8_t v) {
      return i >= 0 && j >= 0 && i < nx && j < ny && material_.value(size_t(j) * nx + i) == v;
    };
    // Air at a cell of row j or beside it in the row; kept for the rows before, at and after the one classified.
    // Loops without branches, over whole rows: vectorised.
    std::vector<uint8_t> air_row(size_t(nx) + 2, 0);  // [i + 1]: cell i of the row is air
    const auto air_beside = [&](long j, std::vector<uint8_t>& out) {
      out.assign(size_t(nx), 0);
      if (j < 0 || j >= ny) return;
      const uint8_t* const cells = material_.values() + size_t(j) * nx;
      uint8_t* const air = air_row.data();
      uint8_t* const beside_air = out.data();
      for (size_t i = 0; i < size_t(nx); ++i) air[i + 1] = cells[i] == LevelMaterial::kAir;
      for (size_t i = 0; i < size_t(nx); ++i) beside_air[i] = air[i] | air[i + 1] | air[i + 2];
    };
    std::array<std::vector<uint8_t>, 3> beside;  // rows j - 1, j, j + 1
    air_beside(-1, beside[0]);
    air_beside(0, beside[1]);
    for (long j = 0; j < ny; ++j) {
      air_beside(j + 1, beside[2]);
      const size_t row = size_t(j) * nx;
      const uint8_t* const cells = material_.values() + row;
      const uint8_t *const below = beside[0].data(), *const at = beside[1].data(), *const above = beside[2].data();
      uint8_t* const closed_row = closed.data() + row;
      uint8_t any_open = 0;
      for (size_t i = 0; i < size_t(nx); ++i) {
        const uint8_t material = cells[i] == LevelMaterial::kMaterial;
        const uint8_t near = below[i] | at[i] | above[i];
        closed_row[i] = material & uint8_t(near ^ 1);
        any_open |= material & near;
      }
      if (any_open)
        for (size_t i = 0; i < size_t(nx); ++i)
          if (cells[i] == LevelMaterial::kMaterial && !closed_row[i]) open.push_back(row + i);
      std::rotate(beside.begin(), beside.begin() + 1, beside.end());
    }
    while (!open.empty()) {
      const size_t c = open.back();
      open.pop_back();
      const long j = material_.row_of(c), i = long(c) - j * nx;
      for (const auto& [di, dj] : {std::pair{1L, 0L}, {-1L, 0L}, {0L, 1L}, {0L, -1L}}) {
        if (!is(i + di, j + dj, LevelMaterial::kMaterial)) continue;
        const size_t k = size_t(j + dj) * nx + i + di;
        if (closed[k]) closed[k] = 0, open.push_back(k);
      }
    }
    return closed;
  }

  // Distances (mm) from the cells at 0 to every other, by a two-pass 3-4 chamfer (Borgefors, "Distance
  // transformations in digital images", 1986): within 8 % of the Euclidean distance.
  // Each row takes its three neighbours in the row before first (independent cells: vectorised), then its
  // neighbour along the row in one scan whose last value stays in a register; a minimum is exact, so the order of
  // the terms changes no distance.
  void chamfer(std::vector<float>& d, long nx, long ny, double cell) const {
    const float a = static_cast<float>(cell), b = static_cast<float>(cell * 4.0 / 3.0);
    // Row `row` after row `near` (the one before it in the pass's order).
    const auto from_near = [&](float* row, const float* near) {
      row[0] = std::min(row[0], std::min(near[0] + a, nx > 1 ? near[1] + b : INFINITY));
      for (long i = 1; i + 1 < nx; ++i)
        row[i] = std::min(std::min(row[i], near[i] + a), std::min(near[i - 1] + b, near[i + 1] + b));
      if (nx > 1) row[nx - 1] = std::min(row[nx - 1], std::min(near[nx - 1] + a, near[nx - 2] + b));
    };
    for (long j = 0; j < ny; ++j) {
      float* row = &d[size_t(j) * nx];
      if (j > 0) from_near(row, row - nx);
      float last = row[0];
      for (long i = 1; i < nx; ++i) last = row[i] = std::min(row[i], last + a);
    }
    for (long j = ny - 1; j >= 0; --j) {
      float* row = &d[size_t(j) * nx];
      if (j + 1 < ny) from_near(row, row + nx);
      float last = row[nx - 1];
      for (long i = nx - 2; i >= 0; --i) last = row[i] = std::min(row[i], last + a);
    }
  }


  // Point k of a helix of radius r around c, kHelixPerTurn a turn.
  static Vec2 helix_point(const Vec2& c, double r, int k) {
    return c + r * Vec2(std::cos(2 * M_PI * k / kHelixPerTurn), std::sin(2 * M_PI * k / kHelixPerTurn));
  }

  // Every point of the helix's circle keeps the cutter out of the part (the depth found on cells is checked).
  bool helix_fits(const Vec2& c, double r) const {
    for (int k = 0; k < kHelixPerTurn; ++k)
      if (!in_part_clearance(helix_point(c, r, k))) return false;
    return in_part_clearance(c);
  }

  void helix(const Vec2& c, double r) {
    ++report_.helices;
    const auto at = [&](int k) { return helix_point(c, r, k); };
    const double top = std::max(top_.highest_under(c, r + R_), z_);
    descend_to(at(0), top);
    const double drop = 2 * M_PI * r * slope_ / kHelixPerTurn;
    int k = 0;
    for (double zc = w_->position().z(); zc > z_ + 1e-9;) {
      zc = std::max(z_, zc - drop);
      const Vec2 p = at(++k);
      w_->plunge_to(Vec3(p.x(), p.y(), zc));
    }
    // The whole disc is cut once the helix is down; a last turn at the level (still the entry, at the plunge
    // feed: it takes the wedge the last turn down left with the cutter's end) flattens its floor.
    cut(c, c, r + R_);
    for (int i = 0; i < kHelixPerTurn; ++i) {
      const Vec2 p = at(++k);
      w_->plunge_to(Vec3(p.x(), p.y(), z_));
    }
    heading_ = (at(k + 1) - at(k)).normalized();
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
    heading_ = (a - b).normalized();
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
  const Surface* surface_ = nullptr;
  PlanFrame f_;
  CutterProfile profile_;
  PlanReport& report_;
  double R_ = 0, limit_ = 0, r_min_ = 0, helix_ = 0, slope_ = 0, cell_ = 0, arc_ = 0;
  double step_ = 0, max_turn_ = 0, target_ = 0, lead_in_ = 0;
  std::array<Vec2, kTurns + 1> turns_;         // cosine and sine of steer()'s turns (material on the right)
  mutable std::array<Step, kTurns + 1> grid_;  // steer()'s turns placed and measured (scratch)
  Vec2 lo_, hi_;
  Toolpath tp_;
  MoveWriter* w_ = nullptr;
  MaterialTop top_;
  BodyGuard guard_;  // the shank and holder over what the levels above left (with a job's material)
  // The level being cut.
  double z_ = 0;
  clip::Paths allowed_;
  // The level's maps and scratch space, kept from level to level (fresh pages cost more than the work on them).
  LevelMaterial material_;
  RegionLookup allowed_lookup_;  // allowed_, for the many tests of where the cutter may go
  LevelMaterial window_;
  std::vector<float> scratch_[2];
  // The air route's search, kept between links so that a link allocates nothing once they are as large as needed.
  std::vector<long> route_came_, route_open_;
  std::vector<uint8_t> route_goal_;
  std::vector<uint8_t> closed_;    // closed_material()
  std::vector<uint8_t> given_up_;  // material cells no pass starts from any more
  std::vector<size_t> cells_;      // the edge cells a search gathered
  size_t steps_ = 0;               // steps steered at the level
  std::vector<size_t> ahead_;      // the material cells a pass's step would cut
  int min_steps_ = kMinPassSteps;  // the fewest cutting steps a pass is made with
  int failed_entries_ = 0;         // entries at the level that took next to nothing
  bool slotting_ = false;          // the wall pass as a slot (level())
  Attempt attempt_;
  Vec2 last_start_ = Vec2::Zero();  // where the last pass began
  Vec2 heading_ = Vec2::UnitX();    // of the cutter's last move at the level
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
