#include "rosmill/plan/tool_body_surface.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace rosmill::core {
namespace {

// A body's drop lowered to the tip it stands for, into the cutter's drop when it is higher.
void raise(Drop& d, const Drop& body, double height) {
  if (!body.touched || (d.touched && body.z - height <= d.z)) return;
  d.z = body.z - height;
  d.touched = true;
}

// The cutter's probe at a level, then the bodies above it asked directly (their questions are few: a body wider than
// the cutter holds the tool only near what stands higher than the stick-out).
class BodyProbe : public LevelProbe {
 public:
  BodyProbe(std::unique_ptr<LevelProbe> cutter, std::function<bool(double, double)> bodies)
      : cutter_(std::move(cutter)), bodies_(std::move(bodies)) {}
  void focus(const Vec2& centre, double radius) override { cutter_->focus(centre, radius); }
  bool held_above(double x, double y) override { return cutter_->held_above(x, y) || bodies_(x, y); }

 private:
  std::unique_ptr<LevelProbe> cutter_;
  std::function<bool(double, double)> bodies_;
};

}  // namespace

ToolBodySurface::ToolBodySurface(const Surface& inner, const Tool& tool, const MaterialTop* material,
                                 double allowance)
    : inner_(inner), grid_(material && material->nx > 0 && material->ny > 0 ? material : nullptr) {
  const Box3 b = inner.bounds();
  const double floor = b.empty() ? 0.0 : b.min.z();
  const double top = std::max(b.empty() ? floor : b.max.z(), grid_ ? grid_->highest() : -INFINITY);
  const Cutter& c = tool.cutter;
  const auto body = [&](double diameter, double height) -> std::unique_ptr<Body> {
    // A body no wider than the cutter stands clear of what the cutter's own cylinder keeps clear.
    if (0.5 * diameter <= c.radius() || top - floor <= height) return nullptr;
    auto out = std::make_unique<Body>(Body{Cutter::flat(diameter + 2 * (allowance + kBodyClearance)), height, {}});
    if (grid_) out->material = grid_->highest_within(out->cylinder.radius());
    return out;
  };
  shank_ = body(c.shank_diameter, c.flute_length);
  holder_ = body(tool.holder_mm(), tool.stick_out_mm());
}

double ToolBodySurface::held_reach() const {
  double reach = inner_.held_reach();
  const Box3 b = inner_.bounds();
  for (const Body* body : {shank_.get(), holder_.get()}) {
    if (!body) continue;
    double beyond = 0;  // the material's grid past the part
    if (grid_ && !b.empty()) {
      const double x1 = grid_->x0 + grid_->nx * grid_->cell, y1 = grid_->y0 + grid_->ny * grid_->cell;
      beyond = std::max({beyond, b.min.x() - grid_->x0, b.min.y() - grid_->y0, x1 - b.max.x(), y1 - b.max.y()});
    }
    reach = std::max(reach, std::max(beyond, inner_.held_reach()) + body->cylinder.radius());
  }
  return reach;
}

double ToolBodySurface::material_under(const Body& b, double x, double y) const {
  return b.material.nx > 0 ? b.material.top_at(Vec2(x, y)) : -INFINITY;
}

Drop ToolBodySurface::drop(const Cutter& cutter, double x, double y) const {
  Drop d = inner_.drop(cutter, x, y);

  for (const Body* b : {shank_.get(), holder_.get()}) {
    if (!b) continue;
    raise(d, inner_.drop(b->cylinder, x, y), b->height);
    const double m = material_under(*b, x, y);
    if (std::isfinite(m)) raise(d, Drop{m, true}, b->height);
  }
  return d;
}

void ToolBodySurface::drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const {
  inner_.drop_many(cutter, xy, n, out);
  std::vector<Drop> body;
  for (const Body* b : {shank_.get(), holder_.get()}) {
    if (!b) continue;
    body.resize(n);
    inner_.drop_many(b->cylinder, xy, n, body.data());
    for (size_t i = 0; i < n; ++i) {
      raise(out[i], body[i], b->height);
      const double m = material_under(*b, xy[i].x(), xy[i].y());
      if (std::isfinite(m)) raise(out[i], Drop{m, true}, b->height);
    }
  }
}

bool ToolBodySurface::held_above(const Cutter& cutter, double x, double y, double z) const {
  if (inner_.held_above(cutter, x, y, z)) return true;
  for (const Body* b : {shank_.get(), holder_.get()})
    if (b && body_holds(*b, x, y, z)) return true;
  return false;
}

bool ToolBodySurface::body_holds(const Body& b, double x, double y, double z) const {
  return material_under(b, x, y) > z + b.height || inner_.held_above(b.cylinder, x, y, z + b.height);
}

std::unique_ptr<LevelProbe> ToolBodySurface::level_probe(const Cutter& cutter, double z) const {
  if (!body_matters()) return inner_.level_probe(cutter, z);
  return std::make_unique<BodyProbe>(inner_.level_probe(cutter, z), [this, z](double x, double y) {
    for (const Body* b : {shank_.get(), holder_.get()})
      if (b && body_holds(*b, x, y, z)) return true;
    return false;
  });
}

SweepHit ToolBodySurface::sweep(const Cutter& cutter, const Vec3& a, const Vec3& b, double floor) const {
  SweepHit hit = inner_.sweep(cutter, a, b, floor);
  for (const Body* body : {shank_.get(), holder_.get()}) {
    if (!body) continue;
    const Vec3 up(0, 0, body->height);
    const SweepHit h = inner_.sweep(body->cylinder, a + up, b + up, hit.depth);
    if (h.depth > hit.depth) hit = h;
    if (body->material.nx == 0) continue;
    // Over the material: every half cell along the move.
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).head<2>().norm() / (0.5 * grid_->cell))));
    for (int k = 0; k <= n; ++k) {
      const Vec3 p = a + (b - a) * (double(k) / n) + up;
      const double depth = material_under(*body, p.x(), p.y()) - p.z();
      if (depth > hit.depth) hit = SweepHit{depth, double(k) / n};
    }
  }
  return hit;
}

}  // namespace rosmill::core
