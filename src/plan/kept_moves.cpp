#include "rosmill/plan/kept_moves.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/cutter/contact.hpp"
#include "rosmill/error.hpp"

namespace rosmill::core {
namespace {

// A piece of a cutting move (the whole move, or a stretch of it between sample points).
struct Piece {
  Vec3 from, to;
  size_t move = 0;  // the original move it belongs to (consecutive pieces of one move are written as one)
  MoveType type = MoveType::Feed;
  double feed = 0.0;
  bool keep = false;
};

// Writes the kept pieces with the links between them.
class RestWriter {
 public:
  // `m` is copied: it is lowered as the kept moves cut it.
  RestWriter(Toolpath& out, const MaterialTop& m, const KeepOptions& o)
      : out_(out), m_(m), o_(o), R_(out.tool.cutter.radius()), profile_(out.tool.cutter), pos_(out.start) {}

  void begin_pass(const std::string& name) { name_ = name, begun_ = false; }

  // One chain of consecutive cutting pieces (no rapid between them in the strategy's path).
  void chain(std::vector<Piece>& pieces) {
    bridge(pieces);
    for (size_t k = 0; k < pieces.size(); ++k) {
      if (!pieces[k].keep) continue;
      if ((pieces[k].from - pos_).norm() > 1e-9 || !down_) link_to(pieces[k].from);
      // Consecutive kept pieces of one move: one move to the last one's end.
      size_t e = k;
      while (e + 1 < pieces.size() && pieces[e + 1].keep && pieces[e + 1].move == pieces[k].move) ++e;
      write({pieces[e].to, pieces[k].type, pieces[k].feed});
      // What the cut certainly took, so that leaving and coming back do not climb over material already gone.
      const double high = std::max(pieces[k].from.z(), pieces[e].to.z());
      m_.lower_along(pieces[k].from.head<2>(), pieces[e].to.head<2>(), R_, high,
                     [&](double d) { return profile_.height(d); });
      k = e;
    }
  }

  void finish() {
    if (down_) write({Vec3(pos_.x(), pos_.y(), out_.safe_z), MoveType::Rapid, 0.0});
  }

 private:
  // Unkept runs shorter than the bridge between kept pieces become kept.
  void bridge(std::vector<Piece>& pieces) const {
    const double limit = std::isnan(o_.bridge) ? 2 * R_ : o_.bridge;
    size_t k = 0;
    while (k < pieces.size() && !pieces[k].keep) ++k;
    while (k < pieces.size()) {
      size_t e = k;
      double len = 0;
      while (e < pieces.size() && !pieces[e].keep) len += (pieces[e].to - pieces[e].from).norm(), ++e;
      if (e < pieces.size() && e > k && len < limit)
        for (size_t i = k; i < e; ++i) pieces[i].keep = true;
      k = e + 1;
      while (k < pieces.size() && pieces[k].keep) ++k;
    }
  }

  void write(const Move& m) {
    if (!begun_) out_.passes.push_back({name_, {}}), begun_ = true;
    out_.passes.back().moves.push_back(m);
    pos_ = m.to;
    down_ = m.type != MoveType::Rapid;
  }

  // The lowest tip at q over which the cutter is clear of the material (the cells under it).
  double clear_at(const Vec2& q) const {
    return m_.clear_height(q, R_, [&](double d) { return profile_.height(d); });
  }

  // Out of the material the cutter stands in (a feed straight up where material left over the design stands
  // above its bottom: the design itself never does, the tip being on it from above), over the material on the
  // way, and down into p.
  void link_to(const Vec3& p) {
    const double c = o_.link_clearance;
    const Vec2 from = pos_.head<2>(), to = p.head<2>();
    if (down_) {
      const double stuck = clear_at(from);
      if (stuck > pos_.z() + 1e-6) write({Vec3(from.x(), from.y(), stuck), MoveType::Feed, out_.tool.feed});
    }
    double over = std::max({m_.highest_along(from, to, R_) + c, pos_.z(), p.z()});
    if (!down_ || !(over < out_.safe_z)) over = out_.safe_z;
    if (pos_.z() < over) write({Vec3(from.x(), from.y(), over), MoveType::Rapid, 0.0});
    if ((from - to).norm() > 0) write({Vec3(to.x(), to.y(), over), MoveType::Rapid, 0.0});
    const double clear = std::max(clear_at(to), p.z()) + o_.approach;
    if (clear < over) write({Vec3(to.x(), to.y(), clear), MoveType::Rapid, 0.0});
    if (pos_.z() > p.z()) write({p, MoveType::Plunge, out_.tool.plunge_feed});
  }

  Toolpath& out_;
  MaterialTop m_;
  const KeepOptions& o_;
  double R_;
  CutterProfile profile_;
  Vec3 pos_;
  bool down_ = false, begun_ = false;
  std::string name_;
};

}  // namespace

Toolpath keep_to_cells(const Toolpath& toolpath, const MaterialTop& material, const KeepOptions& options) {
  material.check("kept moves");
  if (!material.keeps()) throw Error("kept moves", "the material map has no cells to keep to");
  Toolpath out = toolpath;
  out.passes.clear();
  RestWriter writer(out, material, options);
  const double R = toolpath.tool.cutter.radius(), reach = R + material.cell;
  // A cut touches the kept surface between a cell below its tip (the surface's rounding into the cells) and its
  // corner's top (a ball touches up to its radius above the tip).
  const double below = material.cell, above = R + material.cell;
  // Moves are judged every half cell, so that no rest cell is passed between two samples.
  const double step = 0.5 * material.cell;
  Vec3 at = toolpath.start;
  size_t index = 0;
  for (const ToolpathPass& pass : toolpath.passes) {
    writer.begin_pass(pass.name);
    std::vector<Piece> chain;
    for (const Move& m : pass.moves) {
      const Vec3 from = at;
      at = m.to;
      ++index;
      // Rapids and vertical moves break the chain: the writer makes its own ways in and out.
      if (m.type == MoveType::Rapid || (m.to.head<2>() - from.head<2>()).norm() < 1e-12) {
        writer.chain(chain);
        chain.clear();
        continue;
      }
      const int n = std::max(1, static_cast<int>(std::ceil((m.to - from).head<2>().norm() / step)));
      bool near_prev = material.keep_near(from.head<2>(), reach, from.z(), below, above);
      for (int k = 1; k <= n; ++k) {
        const Vec3 q = from + (m.to - from) * (double(k) / n);
        const bool near = material.keep_near(q.head<2>(), reach, q.z(), below, above);
        chain.push_back({k == 1 ? from : chain.back().to, q, index, m.type, m.feed, near || near_prev});
        near_prev = near;
      }
    }
    writer.chain(chain);
  }
  writer.finish();
  return out;
}

Job keep_to_cells(const Job& job, const MaterialTop& material, const KeepOptions& options) {
  Job out;
  for (const Toolpath& tp : job) out.push_back(keep_to_cells(tp, material, options));
  return out;
}

}  // namespace rosmill::core
