#include "rosmill/plan/waterline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "rosmill/parallel.hpp"
#include "rosmill/plan/levels.hpp"
#include "rosmill/plan/raster.hpp"

namespace rosmill::core {
namespace {

constexpr double kAbove = 1e-6;  // CL above the level by more than this is material

// The CL heights on a grid over the part, dropped once for every level.
struct HeightGrid {
  double x0, y0, step;
  int nx, ny;
  std::vector<double> h;
  Vec2 node(int i, int j) const { return Vec2(x0 + i * step, y0 + j * step); }
};

HeightGrid height_grid(const Surface& s, const PlanFrame& f, double step) {
  HeightGrid g;
  // Beyond every place that can hold the cutter: a contour that ran off the grid would be closed by a chord
  // across what holds it.
  const double reach = f.cutter.radius() + f.allowance + s.held_reach() + 2 * step;
  g.step = step;
  g.x0 = f.part.min.x() - reach, g.y0 = f.part.min.y() - reach;
  g.nx = static_cast<int>(std::ceil((f.part.max.x() + reach - g.x0) / step)) + 1;
  g.ny = static_cast<int>(std::ceil((f.part.max.y() + reach - g.y0) / step)) + 1;
  std::vector<Vec2> xy(size_t(g.nx) * g.ny);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) xy[size_t(j) * g.nx + i] = g.node(i, j);
  std::vector<Drop> d(xy.size());
  s.drop_many(f.drop_cutter, xy.data(), xy.size(), d.data());
  g.h.resize(xy.size());
  for (size_t k = 0; k < xy.size(); ++k) g.h[k] = std::max(d[k].z, f.part.min.z()) + f.allowance;
  return g;
}

// The tip height t such that a drop d is above the level (d + allowance > z + kAbove, as cl_height adds it)
// exactly when d > t: the surface is then asked "held above t?", which it answers without the exact drop.
double held_threshold(double z, double allowance) {
  const double target = z + kAbove;
  double t = target - allowance;
  while (t + allowance > target) t = std::nextafter(t, -HUGE_VAL);
  while (std::nextafter(t, HUGE_VAL) + allowance <= target) t = std::nextafter(t, HUGE_VAL);
  return t;
}

class LevelContour {
 public:
  LevelContour(const Surface& s, const PlanFrame& f, const HeightGrid& g, double z)
      : s_(s), f_(f), g_(g), z_(z), floor_in_(material(f.part.min.z() + f.allowance)),
        held_z_(held_threshold(z, f.allowance)),
        probes_([this] { return s_.level_probe(f_.drop_cutter, held_z_); }) {}

  // The chains of crossed grid edges are traced first; the crossings (a bisection each) and then the chords'
  // refinement are independent, and run on both cores.
  std::vector<WallContour> contours() {
    link_cells();
    std::vector<uint64_t> edges;      // the chains one after another
    std::vector<size_t> first = {0};  // chain c is edges[first[c], first[c + 1])
    std::vector<bool> closed;
    trace_chains(edges, first, closed);
    std::vector<Vec3> points(edges.size());
    for_each_index(size_t(0), edges.size(), [&](size_t k) { points[k] = crossing(edges[k]); });
    std::vector<WallContour> out;
    for (size_t c = 0; c + 1 < first.size(); ++c) {
      const Loop chain(points.begin() + first[c], points.begin() + first[c + 1]);
      const std::vector<WallContour> pieces = refine(chain, closed[c]);
      out.insert(out.end(), pieces.begin(), pieces.end());
    }
    return out;
  }

 private:
  static constexpr uint64_t kNoEdge = ~uint64_t(0);

  bool material(double h) const { return h > z_ + kAbove; }
  bool material_at(const Vec2& p) const { return floor_in_ || s_.held_above(f_.drop_cutter, p.x(), p.y(), held_z_); }
  // The same through this thread's probe, focused where the questions are.
  bool material_at(LevelProbe& probe, const Vec2& p) const { return floor_in_ || probe.held_above(p.x(), p.y()); }
  LevelProbe& probe_at(const Vec2& centre, double radius) const {
    LevelProbe& probe = *probes_.local();
    if (!floor_in_) probe.focus(centre, radius);
    return probe;
  }
  bool node_in(int i, int j) const { return material(g_.h[size_t(j) * g_.nx + i]); }

  // Follows the links from each edge not yet used: one chain of edge ids per contour of three or more crossings.
  // A chain that ends where the grid does (an edge with one neighbour) is traced from one of its ends and left open;
  // every other closes on itself.
  void trace_chains(std::vector<uint64_t>& edges, std::vector<size_t>& first, std::vector<bool>& closed) const {
    std::unordered_map<uint64_t, bool> used;
    const auto trace = [&](uint64_t edge) {
      uint64_t prev = kNoEdge, cur = edge;
      while (cur != kNoEdge && !used.count(cur)) {
        used[cur] = true;
        edges.push_back(cur);
        const auto& n = adj_.at(cur);
        const uint64_t next = n[0] != prev ? n[0] : n[1];
        prev = cur;
        cur = next;
      }
      if (edges.size() - first.back() >= 3) first.push_back(edges.size()), closed.push_back(cur == edge);
      else edges.resize(first.back());
    };
    for (const auto& [edge, nb] : adj_)
      if (nb[1] == kNoEdge && !used.count(edge)) trace(edge);
    for (const auto& [edge, nb] : adj_)
      if (!used.count(edge)) trace(edge);
  }

  // Edge ids: 2k for the edge from node k to k + 1 (along x), 2k + 1 from k to k + nx (along y).
  uint64_t edge_id(int i, int j, bool along_y) const { return 2 * (uint64_t(j) * g_.nx + i) + (along_y ? 1 : 0); }

  void connect(uint64_t a, uint64_t b) {
    add(a, b);
    add(b, a);
  }
  void add(uint64_t a, uint64_t b) {
    auto it = adj_.find(a);
    if (it == adj_.end()) adj_.emplace(a, std::array<uint64_t, 2>{b, kNoEdge});
    else it->second[1] = b;
  }

  void link_cells() {
    for (int j = 0; j + 1 < g_.ny; ++j)
      for (int i = 0; i + 1 < g_.nx; ++i) {
        const int c = node_in(i, j) | node_in(i + 1, j) << 1 | node_in(i + 1, j + 1) << 2 | node_in(i, j + 1) << 3;
        if (c == 0 || c == 15) continue;
        const uint64_t e[4] = {edge_id(i, j, false), edge_id(i + 1, j, true), edge_id(i, j + 1, false),
                               edge_id(i, j, true)};
        if (c == 5 || c == 10) {
          const bool centre = material_at(g_.node(i, j) + Vec2(0.5, 0.5) * g_.step);
          // Isolate the corners that differ from the centre.
          const bool cut_c1_c3 = (c == 5) == centre;
          if (cut_c1_c3) connect(e[0], e[1]), connect(e[2], e[3]);
          else connect(e[3], e[0]), connect(e[1], e[2]);
          continue;
        }
        uint64_t ends[2];
        int n = 0;
        const bool in[4] = {bool(c & 1), bool(c & 2), bool(c & 4), bool(c & 8)};
        const int ea[4][2] = {{0, 1}, {1, 2}, {3, 2}, {0, 3}};
        for (int k = 0; k < 4; ++k)
          if (in[ea[k][0]] != in[ea[k][1]]) ends[n++] = e[k];
        if (n == 2) connect(ends[0], ends[1]);
      }
  }

  // Where the contour crosses a grid edge, on the free side, by bisection with the drop-cutter.
  Vec3 crossing(uint64_t id) const {
    const uint64_t k = id / 2;
    const int i = int(k % g_.nx), j = int(k / g_.nx);
    const Vec2 a = g_.node(i, j), b = (id & 1) ? g_.node(i, j + 1) : g_.node(i + 1, j);
    Vec2 in = a, out = b;
    if (!node_in(i, j)) std::swap(in, out);
    const Vec2 p = bisect(probe_at(0.5 * (a + b), 0.5 * g_.step), in, out);
    return Vec3(p.x(), p.y(), z_);
  }

  Vec2 bisect(LevelProbe& probe, Vec2 in, Vec2 out) const {
    while ((in - out).norm() > 0.05 * f_.tolerance) {
      const Vec2 m = 0.5 * (in + out);
      (material_at(probe, m) ? in : out) = m;
    }
    return out;
  }

  // Inserts contour points until every chord's midpoint is within half the tolerance of the contour. A chord no
  // point of which near its middle is clear (it crosses what holds the cutter, however far the search goes) breaks
  // the contour there: the pieces are open.
  std::vector<WallContour> refine(const Loop& loop, bool closed) const {
    const size_t chords = closed ? loop.size() : loop.size() - 1;
    std::vector<Loop> inserted(chords);
    std::vector<char> broken(chords, 0);
    for_each_index(size_t(0), chords,
                   [&](size_t i) { broken[i] = !split(loop[i], loop[(i + 1) % loop.size()], 0, inserted[i]); });
    std::vector<WallContour> out(1);
    out.back().closed = closed;
    for (size_t i = 0; i < loop.size(); ++i) {
      out.back().points.push_back(loop[i]);
      if (i == chords) break;
      if (!broken[i]) {
        out.back().points.insert(out.back().points.end(), inserted[i].begin(), inserted[i].end());
        continue;
      }
      out.emplace_back();  // the chord is not cut: the contour goes on from its other end
      out.back().closed = false;
    }
    // A closed contour broken somewhere is open from the break round to it: its last piece joins its first.
    if (out.size() > 1 && closed) {
      out.back().points.insert(out.back().points.end(), out.front().points.begin(), out.front().points.end());
      out.erase(out.begin());
      for (WallContour& c : out) c.closed = false;
    }
    for (WallContour& c : out) drop_collinear(c.points);
    out.erase(std::remove_if(out.begin(), out.end(), [](const WallContour& c) { return c.points.size() < 2; }),
              out.end());
    return out;
  }

  // The chord a-b made to follow the contour within the tolerance (points inserted into `out`); false when its
  // midpoint lies in what holds the cutter and no clear point is found across it within its own length.
  bool split(const Vec3& a, const Vec3& b, int depth, Loop& out) const {
    const Vec2 d = b.head<2>() - a.head<2>();
    const double len = d.norm();
    if (depth > 10 || len < f_.tolerance) return true;
    const Vec2 m = 0.5 * (a.head<2>() + b.head<2>());
    const Vec2 n(-d.y() / len, d.x() / len);
    double reach = std::min(0.5 * len, g_.step);
    LevelProbe* probe = &probe_at(m, reach);
    const bool m_in = material_at(*probe, m);
    Vec2 c;
    for (;;) {
      const Vec2 p = m - reach * n, q = m + reach * n;
      const bool p_in = material_at(*probe, p), q_in = material_at(*probe, q);
      if (m_in && !p_in) c = bisect(*probe, m, p);
      else if (m_in && !q_in) c = bisect(*probe, m, q);
      else if (!m_in && p_in) c = bisect(*probe, p, m);
      else if (!m_in && q_in) c = bisect(*probe, q, m);
      else if (!m_in) return true;   // clear across its middle: the contour is farther than the chord could stray
      else if (reach >= len) return false;  // deep in what holds the cutter
      else {
        reach = std::min(2 * reach, len);  // the contour is farther off: look further
        probe = &probe_at(m, reach);
        continue;
      }
      break;
    }
    // A free midpoint close enough to the contour needs nothing; a midpoint in material always moves out.
    if (!m_in && (c - m).norm() <= 0.5 * f_.tolerance) return true;
    const Vec3 cp(c.x(), c.y(), z_);
    if (!split(a, cp, depth + 1, out)) return false;
    out.push_back(cp);
    return split(cp, b, depth + 1, out);
  }

  const Surface& s_;
  const PlanFrame& f_;
  const HeightGrid& g_;
  double z_;
  bool floor_in_;   // the part's floor (plus allowance) is above the level: everything is material
  double held_z_;   // held_threshold of the level
  mutable PerThread<std::unique_ptr<LevelProbe>> probes_;  // one per thread
  std::unordered_map<uint64_t, std::array<uint64_t, 2>> adj_;
};

// A level every step-down below the highest CL height, one at every flat face (plus the allowance) and one at the
// part's floor: a wall's foot on a floor, a step or the table is cut by the level at that floor's height, not left
// up to a step-down high between the levels above it.
std::vector<double> default_levels(const Surface& s, const PlanFrame& f, const HeightGrid& g) {
  const double top = *std::max_element(g.h.begin(), g.h.end());
  const double floor = f.part.min.z() + f.allowance;
  return roughing_levels(top, floor, f.stepdown, flat_face_heights(s, f));
}

}  // namespace

struct WaterlineWalls::Grid {
  HeightGrid g;
};

WaterlineWalls::WaterlineWalls(const Surface& surface, const PlanParams& params, size_t levels,
                               const PlanProgress& progress)
    : surface_(surface), f_(make_frame(surface, params)) {
  const double step = std::min(0.25 * f_.cutter.radius(), 0.5);
  // The grid's nodes are dropped once; each level walks every cell (about a tenth of a drop each) and bisects
  // where the contour crosses.
  const double reach = 2 * (f_.cutter.radius() + f_.allowance + surface.held_reach() + 2 * step);
  const double cells = step_count(f_.part.size().x() + reach, step) * step_count(f_.part.size().y() + reach, step);
  const double n_levels = levels > 0 ? double(levels) : step_count(f_.part.size().z(), f_.stepdown);
  check_plan_work("waterline", {cells * (1 + n_levels / 10), cells,
                                count_text(cells, "grid nodes") + " x " + count_text(n_levels, "levels")}, f_);
  grid_ = std::make_unique<const Grid>(Grid{height_grid(surface, f_, step)});
  check_cancel(progress, 0.2);
}

WaterlineWalls::~WaterlineWalls() = default;

std::vector<std::vector<WallContour>> WaterlineWalls::contours(const std::vector<double>& levels,
                                                           const PlanProgress& progress, double from,
                                                           double to) const {
  std::vector<std::vector<WallContour>> out(levels.size());
  parallel_blocks(levels.size(), progress, from, to,
                  [&](size_t i) { out[i] = LevelContour(surface_, f_, grid_->g, levels[i]).contours(); });
  return out;
}

std::vector<std::vector<Loop>> WaterlineWalls::loops(const std::vector<double>& levels, const PlanProgress& progress,
                                                     double from, double to) const {
  const std::vector<std::vector<WallContour>> all = contours(levels, progress, from, to);
  std::vector<std::vector<Loop>> loops(levels.size());
  for (size_t i = 0; i < levels.size(); ++i)
    for (const WallContour& c : all[i]) loops[i].push_back(c.points);
  return loops;
}

std::vector<double> WaterlineWalls::default_levels() const { return core::default_levels(surface_, f_, grid_->g); }

Job waterline_on(const Surface& surface, const PlanParams& params, const WaterlineOptions& options,
                 const PlanProgress& progress, std::vector<std::vector<Loop>>* loops_out) {
  const WaterlineWalls walls(surface, params, options.levels.size(), progress);
  const std::vector<double> levels = options.levels.empty() ? walls.default_levels() : options.levels;
  const std::vector<std::vector<WallContour>> contours = walls.contours(levels, progress, 0.2, 0.95);

  Toolpath tp;
  tp.strategy = "waterline";
  tp.tool = params.tool;
  MoveWriter w(tp, walls.frame());
  for (size_t i = 0; i < levels.size(); ++i) {
    w.begin_pass("z " + std::to_string(levels[i]));
    for (const WallContour& c : contours[i]) {
      w.enter(c.points.front());
      for (size_t k = 1; k < c.points.size(); ++k) w.feed(c.points[k]);
      if (c.closed) w.feed(c.points.front());
      w.retract();
    }
  }
  if (loops_out) {
    loops_out->assign(levels.size(), {});
    for (size_t i = 0; i < levels.size(); ++i)
      for (const WallContour& c : contours[i]) (*loops_out)[i].push_back(c.points);
  }
  check_cancel(progress, 1.0);
  return {tp};
}

Job waterline_strategy(const Surface& surface, const PlanParams& params, const PlanProgress& progress) {
  return waterline_on(surface, params, WaterlineOptions{}, progress);
}

}  // namespace rosmill::core
