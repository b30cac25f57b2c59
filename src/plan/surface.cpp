#include "rosmill/plan/surface.hpp"

#include <algorithm>
#include <cmath>

namespace rosmill::core {

void Surface::drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const {
  for (size_t i = 0; i < n; ++i) out[i] = drop(cutter, xy[i].x(), xy[i].y());
}

bool Surface::held_above(const Cutter& cutter, double x, double y, double z) const {
  const Drop d = drop(cutter, x, y);
  return d.touched && d.z > z;
}

namespace {

class HeldAboveProbe : public LevelProbe {
 public:
  HeldAboveProbe(const Surface& s, const Cutter& c, double z) : s_(s), c_(c), z_(z) {}
  void focus(const Vec2&, double) override {}
  bool held_above(double x, double y) override { return s_.held_above(c_, x, y, z_); }

 private:
  const Surface& s_;
  Cutter c_;
  double z_;
};

}  // namespace

std::unique_ptr<LevelProbe> Surface::level_probe(const Cutter& cutter, double z) const {
  return std::make_unique<HeldAboveProbe>(*this, cutter, z);
}

SweepHit Surface::sweep(const Cutter& cutter, const Vec3& a, const Vec3& b, double floor) const {
  const double step = std::clamp(cutter.radius() / 16, 0.01, 0.05);
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).head<2>().norm() / step)));
  SweepHit hit{floor, 0.0};
  for (int k = 1; k < n; ++k) {
    const double t = double(k) / n;
    const Vec3 p = a + (b - a) * t;
    const double depth = drop(cutter, p.x(), p.y()).z - p.z();
    if (depth > hit.depth) hit = SweepHit{depth, t};
  }
  return hit;
}

bool Surface::skips(double, double, double) const { return false; }

}  // namespace rosmill::core
