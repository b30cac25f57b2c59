#include "rosmill/stock/swept_moves.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/toolpath/canon_arc.hpp"
#include "sweep_kernels.hpp"

namespace rosmill::core::stock {
namespace {

using namespace sweep;

// Chords of a helix within `tolerance` of it, as the removal simulation cuts one (at most 4096).
int helix_chords(const CanonMove& m, double tolerance) {
  const double rho = (m.from.head<2>() - m.centre).norm(), turn = std::abs(arc_sweep(m));
  const double step = rho > tolerance ? 2 * std::acos(1 - tolerance / rho) : M_PI / 2;
  return std::clamp(static_cast<int>(std::ceil(turn / step)), 1, 4096);
}

// A grid of one cell centred on (x, y): the removal kernels read a row of cells, here the one point.
GridSpec point_grid(double x, double y) {
  GridSpec g;
  g.x0 = x - 0.5;
  g.y0 = y - 0.5;
  g.cell = 1.0;
  g.nx = g.ny = 1;
  return g;
}

}  // namespace

SweptMoves::SweptMoves() = default;
SweptMoves::~SweptMoves() = default;
SweptMoves::SweptMoves(const SweptMoves&) = default;
SweptMoves& SweptMoves::operator=(const SweptMoves&) = default;
SweptMoves::SweptMoves(SweptMoves&&) noexcept = default;
SweptMoves& SweptMoves::operator=(SweptMoves&&) noexcept = default;

SweptMoves::SweptMoves(const GridSpec& g, double bin_mm, double near_mm) : near_(near_mm) {
  const int k = std::max(1, static_cast<int>(std::lround(bin_mm / g.cell)));
  bins_.x0 = g.x0;
  bins_.y0 = g.y0;
  bins_.cell = k * g.cell;
  bins_.nx = std::max(1, (g.nx + k - 1) / k);
  bins_.ny = std::max(1, (g.ny + k - 1) / k);
  in_bin_.resize(bins_.cells());
}

size_t SweptMoves::bytes() const {
  size_t n = pieces_.capacity() * sizeof(Piece) + lines_.capacity() * sizeof(LineFrame) +
             in_bin_.capacity() * sizeof(in_bin_[0]);
  for (const auto& b : in_bin_) n += b.capacity() * sizeof(Entry);
  return n;
}

void SweptMoves::add(const MachineProgram& program, double arc_tolerance) {
  if (in_bin_.empty()) throw Error("swept moves", "no grid to keep moves on");
  std::vector<uint16_t> profile_of(program.tools.size());
  for (size_t t = 0; t < program.tools.size(); ++t) {
    const Cutter& c = program.tools[t].cutter;
    size_t k = 0;
    while (k < cutters_.size() && !same_cutter(cutters_[k], c)) ++k;
    if (k == cutters_.size()) {
      cutters_.push_back(c);
      profiles_.emplace_back(c);
      grown_.emplace_back(offset_cutter(c, near_));
    }
    profile_of[t] = static_cast<uint16_t>(k);
  }
  for (const CanonMove& m : program.moves) {
    const uint16_t profile = profile_of[m.tool];
    if (m.shape == MoveShape::Line || m.from.z() == m.to.z()) {
      keep({m.from, m.to, m.centre, m.shape, profile, std::min(m.from.z(), m.to.z())});
      continue;
    }
    const int n = helix_chords(m, arc_tolerance);
    Vec3 a = m.from;
    for (int i = 1; i <= n; ++i) {
      const Vec3 b = i == n ? m.to : move_point(m, static_cast<double>(i) / n);
      keep({a, b, Vec2::Zero(), MoveShape::Line, profile, std::min(a.z(), b.z())});
      a = b;
    }
  }
  for (auto& bin : in_bin_)
    std::stable_sort(bin.begin(), bin.end(), [](const Entry& a, const Entry& b) { return a.lowest < b.lowest; });
}

void SweptMoves::keep(const Piece& p) {
  const double R = grown_[p.profile].R;
  Vec2 lo = p.from.head<2>().cwiseMin(p.to.head<2>()), hi = p.from.head<2>().cwiseMax(p.to.head<2>());
  if (p.shape != MoveShape::Line) {
    CanonMove m;
    m.from = p.from, m.to = p.to, m.centre = p.centre, m.shape = p.shape;
    move_xy_bounds(m, lo, hi);
  }
  lo -= Vec2::Constant(R);
  hi += Vec2::Constant(R);
  const double x1 = bins_.x0 + bins_.nx * bins_.cell, y1 = bins_.y0 + bins_.ny * bins_.cell;
  if (hi.x() < bins_.x0 || hi.y() < bins_.y0 || lo.x() > x1 || lo.y() > y1) return;  // beyond every material
  const auto index = [](double v, double v0, double cell, int n) {
    return std::clamp(static_cast<int>(std::floor((v - v0) / cell)), 0, n - 1);
  };
  const int i0 = index(lo.x(), bins_.x0, bins_.cell, bins_.nx), i1 = index(hi.x(), bins_.x0, bins_.cell, bins_.nx);
  const int j0 = index(lo.y(), bins_.y0, bins_.cell, bins_.ny), j1 = index(hi.y(), bins_.y0, bins_.cell, bins_.ny);
  const uint32_t id = static_cast<uint32_t>(pieces_.size());
  float lowest = static_cast<float>(p.lowest);
  if (double(lowest) > p.lowest) lowest = std::nextafter(lowest, -INFINITY);
  pieces_.push_back(p);
  lines_.push_back(line_frame(p.from, p.to));
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) in_bin_[bins_.index(i, j)].push_back({lowest, id});
}

size_t SweptMoves::bin_of(double x, double y) const {
  const int i = std::clamp(static_cast<int>(std::floor((x - bins_.x0) / bins_.cell)), 0, bins_.nx - 1);
  const int j = std::clamp(static_cast<int>(std::floor((y - bins_.y0) / bins_.cell)), 0, bins_.ny - 1);
  return bins_.index(i, j);
}

double SweptMoves::bottom(const Piece& p, const CutterProfile& cp, double x, double y) const {
  const GridSpec g = point_grid(x, y);
  const LineFrame& f = lines_[size_t(&p - pieces_.data())];
  double d2 = 0;
  if (p.shape != MoveShape::Line) {
    CanonMove m;
    m.from = p.from, m.to = p.to, m.centre = p.centre, m.shape = p.shape;
    const ArcFrame a = arc_frame(m);
    const double ex = x - a.cx, ey = y - a.cy;
    switch (cp.type) {
      case CutterType::FlatEnd: return LevelArcRow<FlatProfile>{a, ex, 1.0, ey, cp.R2, {}}.height(0, d2);
      case CutterType::BallEnd: return LevelArcRow<BallProfile>{a, ex, 1.0, ey, cp.R2, {cp.R, cp.R2}}.height(0, d2);
      case CutterType::BullNose:
        return LevelArcRow<BullProfile>{a, ex, 1.0, ey, cp.R2, {cp.R1, cp.r, cp.r * cp.r}}.height(0, d2);
    }
    return kInf;
  }
  const RowFrame r(f, g, y);
  if (axis_d2(f, r.a(0), r.b(0)) > cp.R2) return kInf;
  const bool level = f.uz == 0.0;
  switch (cp.type) {
    case CutterType::FlatEnd:
      return level ? LevelLineRow<FlatProfile>{f, r, {}}.height(0, d2) : FlatRampRow{f, r, cp.R2}.height(0, d2);
    case CutterType::BallEnd:
      return level ? LevelLineRow<BallProfile>{f, r, {cp.R, cp.R2}}.height(0, d2)
                   : BallRampRow{f, r, cp.R, cp.R2}.height(0, d2);
    case CutterType::BullNose:
      return level ? LevelLineRow<BullProfile>{f, r, {cp.R1, cp.r, cp.r * cp.r}}.height(0, d2)
                   : BullRampRow(f, g, y, cp).height(0, d2);
  }
  return kInf;
}

bool SweptMoves::reaches(uint32_t k, const std::vector<CutterProfile>& profiles, double drop, double x, double y,
                         double z) const {
  const Piece& p = pieces_[k];
  if (p.lowest - drop > z) return false;  // the tip stays above the point
  if (p.shape == MoveShape::Line) {
    const LineFrame& f = lines_[k];
    const double a = f.a(x, y), b = f.b(x, y);
    if (axis_d2(f, a, b) > profiles[p.profile].R2) return false;  // the point is beyond the cutter's reach
  }
  return bottom(p, profiles[p.profile], x, y) - drop <= z;
}

double SweptMoves::lowest_bottom(double x, double y) const {
  double best = kInf;
  if (in_bin_.empty()) return best;
  for (const Entry& e : in_bin_[bin_of(x, y)]) {
    if (e.lowest >= best) break;  // its bottom is no lower than its tip
    const Piece& p = pieces_[e.id];
    best = std::min(best, bottom(p, profiles_[p.profile], x, y));
  }
  return best;
}

bool SweptMoves::removes(double x, double y, double z) const {
  if (in_bin_.empty()) return false;
  for (const Entry& e : in_bin_[bin_of(x, y)]) {
    if (e.lowest > z) break;
    if (reaches(e.id, profiles_, 0.0, x, y, z)) return true;
  }
  return false;
}

bool SweptMoves::comes_near(double x, double y, double z) const {
  if (in_bin_.empty()) return false;
  for (const Entry& e : in_bin_[bin_of(x, y)]) {
    if (e.lowest - near_ > z) break;
    if (reaches(e.id, grown_, near_, x, y, z)) return true;
  }
  return false;
}

double SweptMoves::axis_distance(uint32_t k, double x, double y) const {
  const Piece& p = pieces_[k];
  if (p.shape == MoveShape::Line) {
    const LineFrame& f = lines_[k];
    return std::sqrt(axis_d2(f, f.a(x, y), f.b(x, y)));
  }
  const double rho = (p.from.head<2>() - p.centre).norm();
  return std::abs((Vec2(x, y) - p.centre).norm() - rho);
}

void SweptMoves::gather(const Vec3& c, double radius, std::vector<uint32_t>& ids) const {
  ids.clear();
  if (in_bin_.empty()) return;
  const auto index = [](double v, double v0, double cell, int n) {
    return std::clamp(static_cast<int>(std::floor((v - v0) / cell)), 0, n - 1);
  };
  const int i0 = index(c.x() - radius, bins_.x0, bins_.cell, bins_.nx);
  const int i1 = index(c.x() + radius, bins_.x0, bins_.cell, bins_.nx);
  const int j0 = index(c.y() - radius, bins_.y0, bins_.cell, bins_.ny);
  const int j1 = index(c.y() + radius, bins_.y0, bins_.cell, bins_.ny);
  // Rounding: a move kept when in doubt costs a query a little; one dropped would answer wrong.
  const double top = c.z() + radius + 1e-9;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      for (const Entry& e : in_bin_[bins_.index(i, j)]) {
        const uint32_t k = e.id;
        const Piece& p = pieces_[k];
        const double tip = p.lowest - near_;
        if (tip > top) break;
        const CutterProfile& g = grown_[p.profile];
        const double d = std::max(0.0, axis_distance(k, c.x(), c.y()) - radius);
        if (d > g.R * (1 + 1e-12) + 1e-12 || tip + g.height(std::min(d, g.R)) > top) continue;
        ids.push_back(k);
      }
  if (i0 != i1 || j0 != j1) {  // a move in two bins is listed once
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  }
}

bool SweptMoves::removes_among(const std::vector<uint32_t>& ids, double x, double y, double z) const {
  for (const uint32_t k : ids)
    if (reaches(k, profiles_, 0.0, x, y, z)) return true;
  return false;
}

bool SweptMoves::comes_near_among(const std::vector<uint32_t>& ids, double x, double y, double z) const {
  for (const uint32_t k : ids)
    if (reaches(k, grown_, near_, x, y, z)) return true;
  return false;
}

}  // namespace rosmill::core::stock
