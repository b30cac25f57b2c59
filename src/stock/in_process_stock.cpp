#include "rosmill/stock/in_process_stock.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "grid_walk.hpp"
#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/stock/design_height.hpp"
#include "rosmill/toolpath/canon_arc.hpp"

namespace rosmill::core::stock {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kAxial = 1e-9;  // a direction whose XY part is shorter than this runs along a dexel

struct Range {
  double lo, hi;
};

// Spans minus removed ranges (ascending, possibly touching), appended to `out`.
void subtract(const Span* b, const Span* e, const std::vector<Range>& removed, std::vector<Span>& out) {
  for (const Span* s = b; s != e; ++s) {
    double lo = s->lo;
    for (const Range& r : removed) {
      if (r.hi <= lo || r.lo >= s->hi) continue;
      if (r.lo > lo) out.push_back({static_cast<float>(lo), static_cast<float>(r.lo)});
      lo = std::max(lo, r.hi);
      if (lo >= s->hi) break;
    }
    if (lo < s->hi) out.push_back({static_cast<float>(lo), s->hi});
  }
}

// Adds [lo, hi] to ascending ranges, merging it with the last when they touch.
void add_range(std::vector<Range>& ranges, double lo, double hi) {
  if (!(lo < hi)) return;
  if (!ranges.empty() && lo <= ranges.back().hi) ranges.back().hi = std::max(ranges.back().hi, hi);
  else ranges.push_back({lo, hi});
}

}  // namespace

InProcessStock InProcessStock::box(const Box3& b, double resolution, size_t max_cells, const std::string& where) {
  if (!b.empty() && !(b.size().minCoeff() > 0)) throw Error(where, "the stock box has no volume");
  return InProcessStock(box_dexels(b, stock_grid(b, resolution, max_cells, where)), b);
}

InProcessStock InProcessStock::from_mesh(const Mesh& mesh, double resolution, size_t max_cells,
                                         const std::string& where) {
  return InProcessStock(mesh_dexels(mesh, stock_grid(mesh.bbox, resolution, max_cells, where), where));
}

InProcessStock InProcessStock::from_cloud(const PointCloud& cloud, double table_z, double resolution, int fill_cells,
                                          size_t max_cells, const std::string& where) {
  Box3 b = cloud.bbox;
  if (b.empty()) throw Error(where, "the cloud has no points");
  if (fill_cells < 0) throw Error(where, "the hole fill must be 0 cells or more");
  return InProcessStock(cloud_dexels(cloud, table_z, stock_grid(b, resolution, max_cells, where), fill_cells));
}

size_t InProcessStock::bytes() const {
  size_t n = material_.bytes() + raw_.bytes();
  for (const Envelope& e : envelopes_) n += e.field.top.capacity() * sizeof(float) + e.moves.bytes();
  return n + swept_.bytes();
}

bool InProcessStock::raw_at(const Vec3& p) const {
  if (raw_box_) return (p.array() >= raw_box_->min.array()).all() && (p.array() <= raw_box_->max.array()).all();
  const GridSpec& g = raw_.grid;
  const double fi = std::floor((p.x() - g.x0) / g.cell), fj = std::floor((p.y() - g.y0) / g.cell);
  if (!(fi >= 0 && fj >= 0 && fi < g.nx && fj < g.ny)) return false;
  const size_t c = g.index(static_cast<int>(fi), static_cast<int>(fj));
  for (const Span* s = raw_.begin(c); s != raw_.end(c); ++s)
    if (p.z() >= s->lo && p.z() <= s->hi) return true;
  return false;
}

bool InProcessStock::removed_at(const Vec3& p) const {
  for (const Envelope& e : envelopes_) {
    const Vec3 q = e.setup.to_setup_frame(p);
    if (e.moves.removes(q.x(), q.y(), q.z())) return true;
  }
  return swept_.reaches(p);
}

bool InProcessStock::cut_near(const Vec3& p) const {
  for (const Envelope& e : envelopes_) {
    const Vec3 q = e.setup.to_setup_frame(p);
    if (e.moves.comes_near(q.x(), q.y(), q.z())) return true;
  }
  return swept_.reaches(p, kNearCut);
}

double InProcessStock::near_distance() const { return kNearCut; }

StockProbe::StockProbe(const InProcessStock& stock, double radius)
    : stock_(stock), radius_(radius), moves_(stock.envelopes_.size()) {
  if (!(radius > 0)) throw Error("stock probe", "the radius must be > 0 mm");
}

void StockProbe::aim(const Vec3& p) {
  if ((p - centre_).norm() <= radius_) return;  // false for the first (NaN) centre too
  centre_ = p;
  for (size_t e = 0; e < moves_.size(); ++e) {
    const InProcessStock::Envelope& env = stock_.envelopes_[e];
    env.moves.gather(env.setup.to_setup_frame(p), radius_, moves_[e]);
  }
}

bool StockProbe::removed_at(const Vec3& p) {
  aim(p);
  for (size_t e = 0; e < moves_.size(); ++e) {
    const InProcessStock::Envelope& env = stock_.envelopes_[e];
    const Vec3 q = env.setup.to_setup_frame(p);
    if (env.moves.removes_among(moves_[e], q.x(), q.y(), q.z())) return true;
  }
  return stock_.swept_.reaches(p);
}

bool StockProbe::cut_near(const Vec3& p) {
  aim(p);
  for (size_t e = 0; e < moves_.size(); ++e) {
    const InProcessStock::Envelope& env = stock_.envelopes_[e];
    const Vec3 q = env.setup.to_setup_frame(p);
    if (env.moves.comes_near_among(moves_[e], q.x(), q.y(), q.z())) return true;
  }
  return stock_.swept_.reaches(p, kNearCut);
}

double InProcessStock::raw_extent(const Vec3& p, const Vec3& d, double t_max) const {
  Box3 box = raw_box_.value_or(Box3{});
  if (!raw_box_) {
    const GridSpec& g = raw_.grid;
    box.add(Vec3(g.x0, g.y0, raw_.z_min));
    box.add(Vec3(g.x0 + g.nx * g.cell, g.y0 + g.ny * g.cell, raw_.z_max));
  }
  double t0 = 0, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (p[a] < box.min[a] || p[a] > box.max[a]) return 0;
      continue;
    }
    double n = (box.min[a] - p[a]) / d[a], f = (box.max[a] - p[a]) / d[a];
    if (n > f) std::swap(n, f);
    t0 = std::max(t0, n);
    t1 = std::min(t1, f);
  }
  return t0 > 0 || t1 < t0 ? 0.0 : t1;
}

Box3 InProcessStock::turned_bounds(const SetupFrame& setup) const {
  const GridSpec& g = material_.grid;
  Box3 grid;
  grid.add(Vec3(g.x0, g.y0, material_.z_min));
  grid.add(Vec3(g.x0 + g.nx * g.cell, g.y0 + g.ny * g.cell, material_.z_max));
  return placed(grid, setup.placement);
}

GridSpec InProcessStock::setup_grid(const SetupFrame& setup) const {
  const GridSpec& g = material_.grid;
  const Box3 turned = turned_bounds(setup);
  GridSpec s;
  s.cell = g.cell;
  s.x0 = turned.min.x();
  s.y0 = turned.min.y();
  // The turned box of a grid turned about an axis is the grid itself: its cells fall on the stock's cells.
  s.nx = std::max(1, static_cast<int>(std::ceil(turned.size().x() / g.cell - 1e-6)));
  s.ny = std::max(1, static_cast<int>(std::ceil(turned.size().y() / g.cell - 1e-6)));
  if (s.cells() > 4 * std::max(g.cells(), size_t(1)) + (1u << 20))
    throw Error("setup " + setup.name, "the stock seen from this setup needs " + std::to_string(s.cells()) +
                                           " cells, more than four times the stock's own grid");
  return s;
}

size_t InProcessStock::envelope_index(const SetupFrame& setup) const {
  for (size_t k = 0; k < envelopes_.size(); ++k)
    if (envelopes_[k].setup.same_as(setup)) return k;
  return envelopes_.size();
}

const InProcessStock::Envelope* InProcessStock::envelope_if(const SetupFrame& setup) const {
  const size_t k = envelope_index(setup);
  return k < envelopes_.size() ? &envelopes_[k] : nullptr;
}

InProcessStock::Envelope& InProcessStock::envelope_of(const SetupFrame& setup) {
  const size_t k = envelope_index(setup);
  if (k < envelopes_.size()) return envelopes_[k];
  Envelope e;
  e.setup = setup;
  e.field.grid = setup_grid(setup);
  e.field.top.assign(e.field.grid.cells(), std::numeric_limits<float>::infinity());
  e.moves = SweptMoves(e.field.grid);
  envelopes_.push_back(std::move(e));
  return envelopes_.back();
}

// The highest t where the line R^T (u, v, t) (R: workpiece -> setup) is in material; -infinity when it never is.
double InProcessStock::top_along(const SetupFrame& setup, double u, double v) const {
  const GridSpec& g = material_.grid;
  const Vec3 o = setup.to_workpiece_frame(Vec3(u, v, 0)), a = setup.tool_axis;
  double best = -kInf;
  auto in_cell = [&](int i, int j, double ta, double tb) {
    const size_t c = g.index(i, j);
    for (const Span* s = material_.begin(c); s != material_.end(c); ++s) {
      if (std::abs(a.z()) < kAxial) {
        if (o.z() >= s->lo && o.z() <= s->hi) best = std::max(best, tb);
        continue;
      }
      const double p = (s->lo - o.z()) / a.z(), q = (s->hi - o.z()) / a.z();
      const double lo = std::max(ta, std::min(p, q)), hi = std::min(tb, std::max(p, q));
      if (lo <= hi) best = std::max(best, hi);
    }
  };
  if (a.head<2>().norm() < kAxial) {
    const double fi = std::floor((o.x() - g.x0) / g.cell), fj = std::floor((o.y() - g.y0) / g.cell);
    if (fi >= 0 && fj >= 0 && fi < g.nx && fj < g.ny) in_cell(static_cast<int>(fi), static_cast<int>(fj), -kInf, kInf);
    return best;
  }
  walk_cells(g, o.head<2>(), a.head<2>(), -kInf, kInf, in_cell);
  return best;
}

double InProcessStock::top_at(const SetupFrame& setup, const Envelope* env, const GridSpec& g, int i, int j) const {
  const double t = top_along(setup, g.cx(i), g.cy(j));
  return env ? std::min(t, double(env->field.top[g.index(i, j)])) : t;
}

HeightField InProcessStock::view(const SetupFrame& setup) const {
  HeightField hf;
  hf.grid = setup_grid(setup);
  hf.top.assign(hf.grid.cells(), kNoMaterial);
  hf.cut_by.assign(hf.grid.cells(), HeightField::kNoMove);
  const Envelope* env = envelope_if(setup);
  hf.bottom = turned_bounds(setup).min.z();
  const GridSpec& g = hf.grid;
  for_each_piece<int>(0, g.ny, 1, [&](int begin, int end) {
    for (int j = begin; j < end; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const double t = top_at(setup, env, g, i, j);
        hf.top[g.index(i, j)] = t == -kInf ? kNoMaterial : static_cast<float>(t);
      }
  });
  return hf;
}

// Clips the material's dexels by an envelope: a workpiece line (x, y, z) is at (R p).z = q0.z + z d.z in the
// setup's frame, over the envelope's cell at q0.xy + z d.xy; it is removed where that reaches the envelope.
void InProcessStock::clip(const Envelope& e) {
  const GridSpec& g = material_.grid;
  const GridSpec& eg = e.field.grid;
  const Vec3 d = e.setup.direction_to_setup(Vec3::UnitZ());
  const bool axial = d.head<2>().norm() < kAxial;
  Dexels out;
  out.grid = g;
  out.first.assign(g.cells() + 1, 0);
  out.spans.reserve(material_.spans.size());
  out.z_min = material_.z_min;
  out.z_max = material_.z_max;
  std::vector<Range> removed;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const size_t c = g.index(i, j);
      const Span *b = material_.begin(c), *end = material_.end(c);
      removed.clear();
      if (b != end) {
        const Vec3 q0 = e.setup.to_setup_frame(Vec3(g.cx(i), g.cy(j), 0));
        // The part of [za, zb] where q0.z + z d.z >= level.
        auto cut = [&](double za, double zb, double level) {
          if (!std::isfinite(level)) return;
          if (std::abs(d.z()) < kAxial) {
            if (q0.z() >= level) add_range(removed, za, zb);
            return;
          }
          const double zt = (level - q0.z()) / d.z();
          if (d.z() > 0) add_range(removed, std::max(za, zt), zb);
          else add_range(removed, za, std::min(zb, zt));
        };
        if (axial) {
          const double fi = std::floor((q0.x() - eg.x0) / eg.cell), fj = std::floor((q0.y() - eg.y0) / eg.cell);
          if (fi >= 0 && fj >= 0 && fi < eg.nx && fj < eg.ny)
            cut(-kInf, kInf, e.field.top[eg.index(static_cast<int>(fi), static_cast<int>(fj))]);
        } else {
          walk_cells(eg, q0.head<2>(), d.head<2>(), b->lo, (end - 1)->hi,
                     [&](int u, int v, double za, double zb) { cut(za, zb, e.field.top[eg.index(u, v)]); });
        }
      }
      if (removed.empty()) out.spans.insert(out.spans.end(), b, end);
      else subtract(b, end, removed, out.spans);
      out.first[c + 1] = static_cast<uint32_t>(out.spans.size());
    }
  material_ = std::move(out);
}

RemovalReport InProcessStock::remove(const MachineProgram& program, const SetupFrame& setup,
                                     const SimulationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  RemovalReport r;
  r.moves = program.moves.size();
  for (const CanonMove& m : program.moves) {
    const std::string where = "program move " + std::to_string(m.source);
    if (!m.from.allFinite() || !m.to.allFinite()) throw Error(where, "a position is not finite");
    if (m.tool >= program.tools.size()) throw Error(where, "names a tool the program does not have");
    if (m.is_arc() && m.plane != Plane::XY) throw Error(where, "only arcs in the XY plane (G17) are simulated");
  }
  const double before = volume();
  // The kernel lowers the material's top as seen from the setup: a cell it lowers is a cut into material.
  HeightField work = view(setup);
  SimulationOptions o = options;
  o.trace_finishing = false;
  o.mark_cutting_moves = true;
  const SimulationResult sim = simulate(program, work, o);
  Envelope& e = envelope_of(setup);
  e.moves.add(program, o.arc_tolerance);
  for (size_t c = 0; c < work.top.size(); ++c)
    if (work.cut_by[c] != HeightField::kNoMove) {
      e.field.top[c] = std::min(e.field.top[c], work.top[c]);
      ++r.cut_cells;
    }
  if (r.cut_cells) clip(e);
  r.removed_mm3 = std::max(0.0, before - volume());
  for (size_t k = 0; k < program.moves.size(); ++k) {
    const CanonMove& m = program.moves[k];
    if (m.rapid) continue;
    const double length = move_length(m);
    r.feed_mm += length;
    if (!sim.cutting_moves[k]) r.air_feed_mm += length;
  }
  r.rapid_cut_cells = sim.rapid_cut_cells;
  r.first_rapid_move = sim.first_rapid_cut;
  if (sim.first_rapid_cut != HeightField::kNoMove) r.first_rapid_source = program.moves[sim.first_rapid_cut].source;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// Clips the material's dexels by the swept triangles from `first_triangle` on, each cell's in the order of their
// moves, so that a move which finds only air where an earlier one cut is not marked as cutting.
void InProcessStock::clip_swept(size_t first_triangle, const MultiAxisProgram& program, std::vector<uint8_t>& moves_cut,
                                RemovalReport& r) {
  const GridSpec& g = material_.grid;
  struct Row {
    std::vector<Span> spans;
    std::vector<uint32_t> ends;  // per cell of the row: its spans end here
    std::vector<uint32_t> cut;   // moves that cut in the row
    size_t cut_cells = 0, rapid_cells = 0;
  };
  std::vector<Row> rows(static_cast<size_t>(g.ny));
  for_each_piece<int>(0, g.ny, 1, [&](int begin, int end) {
    std::vector<Span> now, next;
    std::vector<Range> one(1);
    for (int j = begin; j < end; ++j) {
      Row& row = rows[static_cast<size_t>(j)];
      for (int i = 0; i < g.nx; ++i) {
        const size_t c = g.index(i, j);
        now.assign(material_.begin(c), material_.end(c));
        bool cut = false, rapid = false;
        if (!now.empty())
          swept_.at(g.cx(i), g.cy(j), [&](size_t k) {
            if (k < first_triangle || now.empty()) return;
            const SweptTriangle& t = swept_.triangle(k);
            double lo, hi;
            if (!vertical_interval(t, g.cx(i), g.cy(j), lo, hi)) return;
            const bool meets =
                std::any_of(now.begin(), now.end(), [&](const Span& s) { return s.lo < hi && s.hi > lo; });
            if (!meets) return;
            one[0] = {lo, hi};
            next.clear();
            subtract(now.data(), now.data() + now.size(), one, next);
            now.swap(next);
            if (row.cut.empty() || row.cut.back() != t.move) row.cut.push_back(t.move);
            cut = true;
            rapid = rapid || program.moves[t.move].rapid;
          });
        row.cut_cells += cut;
        row.rapid_cells += rapid;
        row.spans.insert(row.spans.end(), now.begin(), now.end());
        row.ends.push_back(static_cast<uint32_t>(row.spans.size()));
      }
    }
  });
  Dexels out;
  out.grid = g;
  out.z_min = material_.z_min;
  out.z_max = material_.z_max;
  out.first.assign(g.cells() + 1, 0);
  size_t total = 0;
  for (const Row& row : rows) total += row.spans.size();
  out.spans.reserve(total);
  for (int j = 0; j < g.ny; ++j) {
    const Row& row = rows[static_cast<size_t>(j)];
    const uint32_t base = static_cast<uint32_t>(out.spans.size());
    out.spans.insert(out.spans.end(), row.spans.begin(), row.spans.end());
    for (int i = 0; i < g.nx; ++i) out.first[g.index(i, j) + 1] = base + row.ends[static_cast<size_t>(i)];
    for (uint32_t m : row.cut) moves_cut[m] = 1;
    r.cut_cells += row.cut_cells;
    r.rapid_cut_cells += row.rapid_cells;
  }
  material_ = std::move(out);
}

RemovalReport InProcessStock::remove(const MultiAxisProgram& program) {
  const auto start = std::chrono::steady_clock::now();
  RemovalReport r;
  r.moves = program.moves.size();
  const size_t first_triangle = swept_.size();
  const double sagitta = 1e-3;  // mm: the steps' chords within a micrometre of the tool's arcs
  for (size_t k = 0; k < program.moves.size(); ++k) {
    const AxisMove& m = program.moves[k];
    const std::string where = "program move " + std::to_string(m.source);
    if (m.tool >= program.tools.size()) throw Error(where, "names a tool the program does not have");
    const Cutter& cutter = program.tools[m.tool].cutter;
    if (cutter.type != CutterType::BallEnd)
      throw Error(where, "only ball-end mills are simulated along multi-axis moves (tool " +
                             std::to_string(program.tools[m.tool].id) + " is not one)");
    try {
      swept_.add_move(m.from, m.axis_from, m.to, m.axis_to, cutter.radius(), cutter.flute_length, sagitta,
                      static_cast<uint32_t>(k));
    } catch (const Error& e) {
      throw Error(where, e.what());
    }
  }
  swept_.index();
  const double before = volume();
  std::vector<uint8_t> cut(program.moves.size(), 0);
  clip_swept(first_triangle, program, cut, r);
  r.removed_mm3 = std::max(0.0, before - volume());
  for (size_t k = 0; k < program.moves.size(); ++k) {
    const AxisMove& m = program.moves[k];
    if (m.rapid) {
      if (cut[k] && r.first_rapid_move == HeightField::kNoMove) {
        r.first_rapid_move = static_cast<uint32_t>(k);
        r.first_rapid_source = m.source;
      }
      continue;
    }
    const double length = (m.to - m.from).norm();
    r.feed_mm += length;
    if (!cut[k]) r.air_feed_mm += length;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::vector<float> InProcessStock::material_above(const Mesh& design, const SetupFrame& setup) const {
  const HeightField v = view(setup);
  const std::vector<float> h = design_heights(placed(design, setup.placement), v.grid, v.bottom);
  std::vector<float> above(v.top.size(), NAN);
  for (size_t c = 0; c < above.size(); ++c)
    if (v.top[c] != kNoMaterial) above[c] = v.top[c] - h[c];
  return above;
}

std::vector<Vec3> InProcessStock::material_corners() const {
  const GridSpec& g = material_.grid;
  std::vector<Vec3> out;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const size_t c = g.index(i, j);
      if (material_.begin(c) == material_.end(c)) continue;
      const double lo = material_.begin(c)->lo, hi = (material_.end(c) - 1)->hi;
      for (int k = 0; k < 8; ++k)
        out.emplace_back(g.x0 + (i + (k & 1)) * g.cell, g.y0 + (j + (k >> 1 & 1)) * g.cell, k & 4 ? hi : lo);
    }
  return out;
}

Box3 InProcessStock::bounds_in(const SetupFrame& setup) const {
  Box3 b;
  for (const Vec3& p : material_corners()) b.add(setup.to_setup_frame(p));
  return b;
}

bool InProcessStock::material_in(const Vec2& lo, const Vec2& hi, double z, const SetupFrame& setup) const {
  if (!lo.allFinite() || !hi.allFinite() || !std::isfinite(z)) throw Error("region", "not finite");
  const GridSpec g = setup_grid(setup);
  const Envelope* env = envelope_if(setup);
  for (int j = g.first_y(lo.y()); j <= g.last_y(hi.y()); ++j)
    for (int i = g.first_x(lo.x()); i <= g.last_x(hi.x()); ++i)
      if (top_at(setup, env, g, i, j) >= z) return true;
  return false;
}

}  // namespace rosmill::core::stock
